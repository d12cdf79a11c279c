// The six OSC-ALKS OpenDRIVE roads (../shared/data/openscenario/road_networks) read, and
// their geometry agrees with what the files' author computed: every geometry record's start
// pose (written by the author's tool) is where the previous record ends.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <pugixml.hpp>

#include "opendrive/sumo_net.hpp"
#include "opendrive/xodr_reader.hpp"
#include "support/cli_runner.hpp"

namespace {

using namespace orch::opendrive;

std::string road_file(const std::string& name) {
  return std::string(ORCH_SHARED_DATA_DIR) + "/openscenario/road_networks/" + name + ".xodr";
}

TEST(OpenDriveAlksRoads, EveryRecordStartsWhereThePreviousEnds) {
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(ORCH_SHARED_DATA_DIR) +
                                                               "/openscenario/road_networks")) {
    const RoadNetwork net = read_xodr_file(entry.path().string());
    ASSERT_EQ(net.roads().size(), 1u) << entry.path();
    const auto& geometries = net.roads().front().plan_view.geometries();
    for (std::size_t i = 1; i < geometries.size(); ++i) {
      const Pose2 end = evaluate(geometries[i - 1], geometries[i - 1].length);
      EXPECT_NEAR(end.x, geometries[i].start.x, 1e-6) << entry.path() << " record " << i;
      EXPECT_NEAR(end.y, geometries[i].start.y, 1e-6) << entry.path() << " record " << i;
      EXPECT_NEAR(std::remainder(end.heading - geometries[i].start.heading, 2 * M_PI), 0.0, 1e-9);
      ++checked;
    }
  }
  // different_curvatures has line, spiral, arc, spiral, ... records.
  EXPECT_GE(checked, 5);
}

TEST(OpenDriveAlksRoads, EgoLaneCentreIsEightMetresRightOfTheReferenceLine) {
  // Lane -4: border 2 + border 0.75 + driving 3.5 + half of 3.5 = 8 m to the right; the
  // reference positions of the OSC-ALKS README put the ego at y = -8 on the straight road.
  const RoadNetwork net = read_xodr_file(road_file("alks_road_straight"));
  const Pose2 p = net.lane_pose("0", -4, 5.0, 0.0);
  EXPECT_NEAR(p.x, 5.0, 1e-12);
  EXPECT_NEAR(p.y, -8.0, 1e-12);
  EXPECT_EQ(net.road("0").section_at(0).lane(-6)->type, "stop");
  // The 3 m hard shoulder (-6) lies outside the three driving lanes: centre 14.75 m right.
  EXPECT_NEAR(net.lane_pose("0", -6, 500.0, 0.0).y, -(2.0 + 0.75 + 3 * 3.5 + 1.5), 1e-12);
  EXPECT_EQ(net.road("0").lane_at(500.0, -13.0), -5);
  EXPECT_EQ(net.road("0").lane_at(500.0, -13.5), -6);
}

TEST(OpenDriveAlksRoads, CurvedRoadLaneCentreLiesOnItsConcentricCircle) {
  // Right curve, radius 250 m, centre at (0, -250); lane -4 runs at radius 250 - 8.
  const RoadNetwork net = read_xodr_file(road_file("alks_road_right_radius_250m"));
  for (const double s : {0.0, 300.0, 700.0}) {
    const Pose2 p = net.lane_pose("0", -4, s, 0.0);
    EXPECT_NEAR(std::hypot(p.x, p.y + 250.0), 242.0, 1e-9);
    EXPECT_NEAR(p.heading, -s / 250.0, 1e-12);
    const auto back = net.to_road(p.x, p.y);
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(back->s, s, 1e-6);
    EXPECT_NEAR(back->t, -8.0, 1e-6);
  }
}

TEST(OpenDriveAlksRoads, ConvertedNetHasThreeMotorwayLanesAndAShoulderPerDirection) {
  orch::test::TempDir cache;
  const SumoNet net = convert_to_sumo_net(road_file("alks_road_right_radius_250m"), cache.path());
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(net.net_file.c_str()));
  for (const char* edge : {"-0", "0"}) {
    std::vector<pugi::xml_node> lanes;
    for (const pugi::xml_node lane : doc.child("net").find_child_by_attribute("edge", "id", edge).children("lane"))
      lanes.push_back(lane);
    ASSERT_EQ(lanes.size(), 4u) << edge;
    EXPECT_STREQ(lanes[0].attribute("allow").value(), "authority") << edge;  // the hard shoulder
    for (std::size_t i = 1; i < 4; ++i) EXPECT_NEAR(lanes[i].attribute("speed").as_double(), 130 / 3.6, 0.01);
  }
}

}  // namespace
