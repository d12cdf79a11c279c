// OpenSCENARIO positions resolved on OpenDRIVE geometry (map/position_resolver.hpp): values by hand on a straight
// three-lane road and on an arc (closed form).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "map/position_resolver.hpp"

namespace orch::position {
namespace {

using opendrive::Pose2;

// Right lanes -1 (border 2 m), -2, -3 (driving 3.5 m); reference line straight along +x for
// 300 m, then an arc of radius 500 m to the left.
const char* kRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="600" junction="-1">
 <planView>
  <geometry s="0" x="0" y="0" hdg="0" length="300"><line/></geometry>
  <geometry s="300" x="300" y="0" hdg="0" length="300"><arc curvature="0.002"/></geometry>
 </planView>
 <lanes><laneSection s="0"><right>
  <lane id="-1" type="border"><width sOffset="0" a="2" b="0" c="0" d="0"/></lane>
  <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
  <lane id="-3" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 </right><left>
  <lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 </left></laneSection></lanes>
</road></OpenDRIVE>)";

class Positions : public ::testing::Test {
 protected:
  Positions() : roads_(opendrive::read_xodr_text(kRoad, "road.xodr")), resolver_(roads_) {}
  ResolvedPosition resolve(const Position& p) {
    return resolver_.resolve(p, [&](const std::string& name) -> std::optional<Pose2> {
      const auto it = entities_.find(name);
      if (it == entities_.end()) return std::nullopt;
      return it->second;
    });
  }
  opendrive::RoadNetwork roads_;
  PositionResolver resolver_;
  std::map<std::string, Pose2> entities_;
};

TEST_F(Positions, LanePositionIsTheLaneCentrePlusOffset) {
  const ResolvedPosition r = resolve(LanePosition{"0", -2, 50.0, 0.25, std::nullopt});
  EXPECT_NEAR(r.pose.x, 50.0, 1e-12);
  EXPECT_NEAR(r.pose.y, -(2.0 + 1.75) + 0.25, 1e-12);
  EXPECT_NEAR(r.pose.heading, 0.0, 1e-12);
  EXPECT_EQ(r.lane, -2);
  // On the arc: centre of the circle (300, 500); lane -3 centre runs at radius 500 + 7.25.
  const ResolvedPosition a = resolve(LanePosition{"0", -3, 400.0, 0.0, Orientation{true, 0.1}});
  const double angle = 100.0 / 500.0;
  EXPECT_NEAR(a.pose.x, 300 + 507.25 * std::sin(angle), 1e-9);
  EXPECT_NEAR(a.pose.y, 500 - 507.25 * std::cos(angle), 1e-9);
  EXPECT_NEAR(a.pose.heading, angle + 0.1, 1e-12);
  EXPECT_THROW((void)resolve(LanePosition{"0", -4, 10.0, 0.0, std::nullopt}), MapError);
  EXPECT_THROW((void)resolve(LanePosition{"7", -2, 10.0, 0.0, std::nullopt}), MapError);
}

// On left lane 1 (right-hand traffic: it drives against s) a LanePosition's relative
// Orientation turns from the lane's driving direction, a road position's from the road's s,
// and an Orientation left out is relative h=0: as esmini places them (the standard is
// ambiguous for the LanePosition: docs/openscenario.md, Positions).
TEST_F(Positions, ALanePositionsRelativeHeadingIsTheLanesDrivingDirection) {
  EXPECT_NEAR(resolve(LanePosition{"0", 1, 50.0, 0.0, Orientation{true, 0.0}}).pose.heading, M_PI, 1e-12);
  EXPECT_NEAR(resolve(LanePosition{"0", 1, 50.0, 0.0, std::nullopt}).pose.heading, M_PI, 1e-12);
  EXPECT_NEAR(std::remainder(resolve(LanePosition{"0", 1, 50.0, 0.0, Orientation{true, M_PI}}).pose.heading, 2 * M_PI),
              0.0, 1e-12);  // h = pi: along s, as a left-hand-traffic file places it
  EXPECT_NEAR(resolve(LanePosition{"0", -2, 50.0, 0.0, Orientation{true, 0.2}}).pose.heading, 0.2, 1e-12);
  EXPECT_NEAR(resolve(LanePosition{"0", 1, 50.0, 0.0, Orientation{false, 0.2}}).pose.heading, 0.2, 1e-12);
  EXPECT_NEAR(resolve(RoadPosition{"0", 50.0, 1.75, Orientation{true, 0.0}}).pose.heading, 0.0, 1e-12);
  entities_["Ego"] = Pose2{100.0, 1.75, M_PI};  // on lane 1
  EXPECT_NEAR(resolve(RelativeLanePosition{"Ego", 0, -30.0, 0.0, Orientation{true, 0.0}}).pose.heading, 0.0, 1e-12);
}

TEST_F(Positions, RelativeLanePositionCountsLanesAcrossTheCentre) {
  entities_["Ego"] = Pose2{100.0, -3.75, 0.0};  // lane -2
  const ResolvedPosition right = resolve(RelativeLanePosition{"Ego", -1, 30.0, 0.0, std::nullopt});
  EXPECT_NEAR(right.pose.x, 130.0, 1e-9);
  EXPECT_NEAR(right.pose.y, -(2.0 + 3.5 + 1.75), 1e-9);
  EXPECT_EQ(right.lane, -3);
  // Two lanes to the left of -2: -1, then (skipping 0) 1.
  const ResolvedPosition left = resolve(RelativeLanePosition{"Ego", 2, 0.0, 0.5, std::nullopt});
  EXPECT_NEAR(left.pose.y, 1.75 + 0.5, 1e-9);
  EXPECT_EQ(left.lane, 1);
  EXPECT_THROW((void)resolve(RelativeLanePosition{"Nobody", 0, 0.0, 0.0, std::nullopt}), MapError);
}

TEST_F(Positions, RoadWorldAndObjectRelativePositions) {
  const ResolvedPosition road = resolve(RoadPosition{"0", 20.0, -1.0, std::nullopt});
  EXPECT_NEAR(road.pose.y, -1.0, 1e-12);
  ASSERT_TRUE(road.road.has_value());
  EXPECT_NEAR(road.road->s, 20.0, 1e-12);

  entities_["A"] = Pose2{10.0, -5.0, M_PI / 2};
  const ResolvedPosition world = resolve(RelativeWorldPosition{"A", 1.0, 2.0, Orientation{false, 0.3}});
  EXPECT_NEAR(world.pose.x, 11.0, 1e-12);
  EXPECT_NEAR(world.pose.y, -3.0, 1e-12);
  EXPECT_NEAR(world.pose.heading, 0.3, 1e-12);
  // In A's own frame (facing +y): 4 m ahead, 1 m to its left = (-1, +4) in the world.
  const ResolvedPosition object = resolve(RelativeObjectPosition{"A", 4.0, 1.0, std::nullopt});
  EXPECT_NEAR(object.pose.x, 9.0, 1e-12);
  EXPECT_NEAR(object.pose.y, -1.0, 1e-12);
  EXPECT_NEAR(object.pose.heading, M_PI / 2, 1e-12);

  const ResolvedPosition on_arc = resolve(WorldPosition{300 + 500 * std::sin(0.2), 500 - 500 * std::cos(0.2), 0.2});
  ASSERT_TRUE(on_arc.road.has_value());
  EXPECT_NEAR(on_arc.road->s, 400.0, 1e-6);
  EXPECT_NEAR(on_arc.road->t, 0.0, 1e-6);
  entities_["C"] = on_arc.pose;
  const ResolvedPosition ahead = resolve(RelativeRoadPosition{"C", 50.0, -2.0, std::nullopt});
  EXPECT_NEAR(ahead.pose.x, 300 + 502 * std::sin(0.3), 1e-6);
  EXPECT_NEAR(ahead.pose.y, 500 - 502 * std::cos(0.3), 1e-6);
  EXPECT_NEAR(ahead.pose.heading, 0.3, 1e-9);
}

}  // namespace
}  // namespace orch::position
