// OpenDRIVE links: the lane graph (road to road, a contact point that flips the direction,
// a 3-way junction, lane sections) and route planning by strategy, on hand-written roads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "opendrive/lane_graph.hpp"
#include "opendrive/route_planner.hpp"
#include "opendrive/xodr_reader.hpp"
#include "unit/xodr_network_snippets.hpp"

namespace orch::opendrive {
namespace {

using test::xodr_connection;
using test::xodr_file;
using test::xodr_road;
using test::XodrRoad;

constexpr double kPi = std::numbers::pi;

std::vector<std::string> roads_of(const std::vector<LaneEntry>& entries) {
  std::vector<std::string> out;
  for (const auto& e : entries) out.push_back(e.road_id);
  return out;
}

RoadNetwork two_in_a_row() { return read_xodr_text(test::xodr_two_in_a_row(), "row.xodr"); }
RoadNetwork contact_end() { return read_xodr_text(test::xodr_contact_end(), "flip.xodr"); }
RoadNetwork three_way() { return read_xodr_text(test::xodr_three_way(), "junction.xodr"); }

TEST(OpenDriveLaneGraph, RoadLinksAndLaneLinksAreRead) {
  const RoadNetwork roads = three_way();
  const Road& one = roads.road("1");
  EXPECT_EQ(one.successor.kind, RoadLink::Kind::Junction);
  EXPECT_EQ(one.successor.id, "J");
  const Road& c10 = roads.road("10");
  EXPECT_EQ(c10.predecessor.kind, RoadLink::Kind::Road);
  EXPECT_EQ(c10.predecessor.contact, ContactPoint::End);
  EXPECT_EQ(c10.sections[0].lane(-1)->successor, -1);
  ASSERT_NE(roads.junction("J"), nullptr);
  ASSERT_EQ(roads.junction("J")->connections.size(), 3u);
  EXPECT_EQ(roads.junction("J")->connections[2].contact, ContactPoint::End);
  EXPECT_EQ(roads.junction("J")->connections[2].lane_links[0].to, 1);
}

TEST(OpenDriveLaneGraph, ALinkToAnUnknownRoadIsAnErrorNamingIt) {
  try {
    (void)read_xodr_text(xodr_file(xodr_road({"1", 0, 0, 0, 100, "", "road 22 start"})), "bad.xodr");
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.xodr"), std::string::npos) << what;
    EXPECT_NE(what.find("unknown road \"22\""), std::string::npos) << what;
  }
}

TEST(OpenDriveLaneGraph, TwoRoadsInARowContinueBothWays) {
  const RoadNetwork roads = two_in_a_row();
  const auto forward = next_lanes(roads, "1", -1);
  ASSERT_EQ(forward.size(), 1u);
  EXPECT_EQ(forward[0].road_id, "2");
  EXPECT_EQ(forward[0].lane, -1);
  EXPECT_EQ(forward[0].s, 0.0);
  EXPECT_EQ(forward[0].direction, 1);
  const auto back = next_lanes(roads, "2", 1);  // lane 1 drives towards s = 0
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].road_id, "1");
  EXPECT_EQ(back[0].lane, 1);
  EXPECT_EQ(back[0].s, 100.0);
  EXPECT_EQ(back[0].direction, -1);
  EXPECT_TRUE(next_lanes(roads, "2", -1).empty());  // road 2's end leads nowhere
}

TEST(OpenDriveLaneGraph, ContactPointEndFlipsTheDirectionWithTheLaneCentreContinuous) {
  const RoadNetwork roads = contact_end();
  const auto next = next_lanes(roads, "1", -1);
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].road_id, "3");
  EXPECT_EQ(next[0].lane, 1);
  EXPECT_EQ(next[0].s, 50.0);
  EXPECT_EQ(next[0].direction, -1);
  const Pose2 out = roads.lane_pose("1", -1, 100.0, 0.0);
  const Pose2 in = roads.lane_pose("3", 1, 50.0, 0.0);
  EXPECT_NEAR(out.x, in.x, 1e-9);
  EXPECT_NEAR(out.y, in.y, 1e-9);
  EXPECT_NEAR(turn_angle(roads, "1", -1, next[0]), 0.0, 1e-9);
  // And back: lane -1 of road 3 drives along its s to s = 50, onto lane 1 of road 1.
  const auto back = next_lanes(roads, "3", -1);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].road_id, "1");
  EXPECT_EQ(back[0].lane, 1);
  EXPECT_EQ(back[0].direction, -1);
}

TEST(OpenDriveLaneGraph, JunctionConnectionsOfTheIncomingRoadAndTheStraightestDefault) {
  const RoadNetwork roads = three_way();
  const auto next = next_lanes(roads, "1", -1);
  ASSERT_EQ(roads_of(next), (std::vector<std::string>{"11", "10"}));  // file order
  EXPECT_EQ(next[0].junction, "J");
  EXPECT_NEAR(turn_angle(roads, "1", -1, next[0]), kPi / 2, 1e-6);  // the left turn
  EXPECT_NEAR(turn_angle(roads, "1", -1, next[1]), 0.0, 1e-9);
  const auto choice = straightest_next(roads, "1", -1);
  ASSERT_TRUE(choice);
  EXPECT_EQ(choice->road_id, "10");
  // The connecting roads lead on by their road links.
  EXPECT_EQ(roads_of(next_lanes(roads, "11", -1)), std::vector<std::string>{"3"});
  EXPECT_EQ(roads_of(next_lanes(roads, "10", -1)), std::vector<std::string>{"2"});
  // Road 2's lane 1 comes back on the connecting road's lane 1, entered at its end.
  const auto back = next_lanes(roads, "2", 1);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].road_id, "10");
  EXPECT_EQ(back[0].lane, 1);
  EXPECT_EQ(back[0].s, 20.0);
  // Lane 1 of road 1 drives away from the junction: nothing continues it at road 1's start.
  EXPECT_TRUE(next_lanes(roads, "1", 1).empty());
}

TEST(OpenDriveLaneGraph, ADirectJunctionLinksTheIncomingRoadToItsLinkedRoad) {
  // OpenDRIVE 1.7: road 1 splits into roads 2 and 3 with no connecting roads between.
  const std::string body = xodr_road({"1", 0, 0, 0, 100, "", "junction D"}) +
                           xodr_road({"2", 100, 0, 0, 100, "junction D", ""}) +
                           xodr_road({"3", 100, 0, 0.2, 100, "junction D", ""}) +
                           R"(<junction id="D" type="direct"><connection id="0" incomingRoad="1" linkedRoad="3" contactPoint="start"><laneLink from="-1" to="-1"/></connection>)"
                           R"(<connection id="1" incomingRoad="1" linkedRoad="2" contactPoint="start"><laneLink from="-1" to="-1"/></connection></junction>)";
  const RoadNetwork roads = read_xodr_text(xodr_file(body), "direct.xodr");
  const auto next = next_lanes(roads, "1", -1);
  EXPECT_EQ(roads_of(next), (std::vector<std::string>{"3", "2"}));
  EXPECT_EQ(straightest_next(roads, "1", -1)->road_id, "2");
}

TEST(OpenDriveLaneGraph, LaneLinksRenumberLanesBetweenSections) {
  // Section 2 adds an inner right lane: lane -1 of section 1 becomes lane -2.
  const std::string road = R"(<road id="1" length="100" junction="-1">
<planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
<lanes><laneSection s="0"><center><lane id="0" type="none"/></center>
<right><lane id="-1" type="driving"><link><successor id="-2"/></link><width sOffset="0" a="3.5"/></lane></right></laneSection>
<laneSection s="60"><center><lane id="0" type="none"/></center>
<right><lane id="-1" type="driving"><width sOffset="0" a="3.5"/></lane>
<lane id="-2" type="driving"><link><predecessor id="-1"/></link><width sOffset="0" a="3.5"/></lane></right></laneSection></lanes></road>)";
  const RoadNetwork roads = read_xodr_text(xodr_file(road), "sections.xodr");
  const Road& r = roads.road("1");
  EXPECT_EQ(section_index(r, 59.0), 0u);
  EXPECT_EQ(section_index(r, 60.0), 1u);
  EXPECT_EQ(lane_in_next_section(r, 0, -1, 1), -2);
  EXPECT_EQ(lane_in_next_section(r, 1, -2, -1), -1);
  EXPECT_EQ(lane_in_next_section(r, 1, -1, -1), -1);  // no link: the same id, which section 1 has
  EXPECT_EQ(lane_at_road_exit(r, -1, 10.0), -2);
}

// Road 1 -> J1 -> {12 -> road 2 (100 m, 10 m/s) -> J3 -> 25 -> road 5 (50 m) -> J2,
//                  13 -> road 3 (300 m, 40 m/s) -> J2} ; J2 -> {54, 34} -> road 4.
// Geometry is arbitrary (lines); plans depend on lengths, speeds and junctions only.
RoadNetwork two_ways() {
  std::string body;
  body += xodr_road({"1", 0, 0, 0, 100, "", "junction J1"});
  XodrRoad two{"2", 0, 50, 0, 100, "junction J1", "junction J3"};
  two.right_speed = 10;
  body += xodr_road(two);
  XodrRoad three{"3", 0, 100, 0, 300, "junction J1", "junction J2"};
  three.right_speed = 40;
  body += xodr_road(three);
  body += xodr_road({"5", 0, 150, 0, 50, "junction J3", "junction J2"});
  body += xodr_road({"4", 0, 200, 0, 100, "junction J2", ""});
  body += xodr_road({"12", 0, 250, 0, 10, "road 1 end", "road 2 start", "J1"});
  body += xodr_road({"13", 0, 260, 0, 10, "road 1 end", "road 3 start", "J1"});
  body += xodr_road({"25", 0, 270, 0, 10, "road 2 end", "road 5 start", "J3"});
  body += xodr_road({"54", 0, 280, 0, 10, "road 5 end", "road 4 start", "J2"});
  body += xodr_road({"34", 0, 290, 0, 10, "road 3 end", "road 4 start", "J2"});
  body += "<junction id=\"J1\">" + xodr_connection("a", "1", "12", "start") + xodr_connection("b", "1", "13", "start") +
          "</junction>";
  body += "<junction id=\"J3\">" + xodr_connection("a", "2", "25", "start") + "</junction>";
  body += "<junction id=\"J2\">" + xodr_connection("a", "5", "54", "start") + xodr_connection("b", "3", "34", "start") +
          "</junction>";
  return read_xodr_text(xodr_file(body), "two_ways.xodr");
}

TEST(OpenDriveRoutePlanner, EachStrategyPicksItsWay) {
  const RoadNetwork roads = two_ways();
  const RoutePoint from{"1", 10, -1};
  const RoutePoint to{"4", 50, -1};
  const std::vector<std::string> via_2{"12", "2", "25", "5", "54", "4"};
  const std::vector<std::string> via_3{"13", "3", "34", "4"};
  // Shortest: 90 + 10 + 100 + 10 + 50 + 10 + 50 = 320 m against 90 + 10 + 300 + 10 + 50 = 460 m.
  EXPECT_EQ(roads_of(plan_route(roads, from, to, RouteStrategy::Shortest).value()), via_2);
  // Fastest: road 2 at 10 m/s takes 10 s alone; road 3 at 40 m/s 7.5 s (others 100 km/h).
  EXPECT_EQ(roads_of(plan_route(roads, from, to, RouteStrategy::Fastest).value()), via_3);
  // LeastIntersections: J1, J2 against J1, J3, J2.
  EXPECT_EQ(roads_of(plan_route(roads, from, to, RouteStrategy::LeastIntersections).value()), via_3);
  // Random: one of the two, the same each time.
  const auto random = roads_of(plan_route(roads, from, to, RouteStrategy::Random).value());
  EXPECT_TRUE(random == via_2 || random == via_3);
  EXPECT_EQ(roads_of(plan_route(roads, from, to, RouteStrategy::Random).value()), random);
}

TEST(OpenDriveRoutePlanner, AheadOnTheSameRoadNeedsNoLinkAndBehindIsUnreachable) {
  const RoadNetwork roads = two_in_a_row();
  EXPECT_TRUE(plan_route(roads, {"1", 10, -1}, {"1", 80, -1}, RouteStrategy::Shortest).value().empty());
  EXPECT_EQ(roads_of(plan_route(roads, {"1", 10, -1}, {"2", 20, -1}, RouteStrategy::Shortest).value()),
            std::vector<std::string>{"2"});
  EXPECT_FALSE(plan_route(roads, {"1", 80, -1}, {"1", 10, -1}, RouteStrategy::Shortest));
  // Road 2's lane 1 drives back to road 1: reachable that way round only.
  EXPECT_EQ(roads_of(plan_route(roads, {"2", 20, 1}, {"1", 50, 1}, RouteStrategy::Shortest).value()),
            std::vector<std::string>{"1"});
  EXPECT_FALSE(plan_route(roads, {"2", 20, 1}, {"1", 50, -1}, RouteStrategy::Shortest));
}

TEST(OpenDriveRoutePlanner, DefaultContinuationGoesStraightOnUntilTheNetworkEnds) {
  const RoadNetwork roads = three_way();
  EXPECT_EQ(roads_of(default_continuation(roads, "1", -1)), (std::vector<std::string>{"10", "2"}));
  EXPECT_TRUE(default_continuation(roads, "2", -1).empty());
}

}  // namespace
}  // namespace orch::opendrive
