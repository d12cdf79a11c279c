// A storyboard entity following its lane faces where it moves: where the lane's centre
// drifts sideways (a lane beside it widening, as road 202 of esmini's
// multi_intersections.xodr shifts its lanes under trailers.xosc), its heading turns with
// the lane, in both directions of travel and standing; the heading is checked against the
// direction of the entity's own motion over a step.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "opendrive/xodr_reader.hpp"
#include "openscenario/entity_motion.hpp"

namespace orch::openscenario {
namespace {

// A straight road along +x, 200 m: lanes 1 and -1 widen from 3.5 m by 0.05 m per metre of
// s (b = 0.05), lanes 2 and -2 keep 3.5 m, so the centres of lanes 2 and -2 drift outward
// at dt/ds = +-0.05 and those of lanes 1 and -1 at +-0.025.
const char* kWideningRoad = R"(<?xml version="1.0"?>
<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="1" length="200" junction="-1">
  <planView><geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
  <lanes><laneSection s="0">
    <left>
      <lane id="1" type="driving"><width sOffset="0" a="3.5" b="0.05" c="0" d="0"/></lane>
      <lane id="2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
    </left>
    <center><lane id="0" type="none"/></center>
    <right>
      <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0.05" c="0" d="0"/></lane>
      <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
    </right>
  </laneSection></lanes>
</road></OpenDRIVE>)";

EntityState on_lane(const opendrive::RoadNetwork& roads, int lane, double s, double speed) {
  EntityState state;
  state.placed = true;
  state.road_id = "1";
  state.lane = lane;
  state.s = s;
  state.speed = speed;
  update_pose(state, roads);
  return state;
}

double wrapped(double angle) { return std::remainder(angle, 2 * std::numbers::pi); }

TEST(LaneHeading, AnEntityTurnsWithItsLanesCentreAndFacesWhereItMoves) {
  const auto roads = opendrive::read_xodr_text(kWideningRoad, "widening.xodr");
  struct Case {
    int lane;
    double slope;  // the lane centre's dt/ds
  };
  for (const Case c : {Case{-2, -0.05}, Case{-1, -0.025}, Case{1, 0.025}, Case{2, 0.05}}) {
    EntityState car = on_lane(roads, c.lane, 100, 20);
    const int direction = c.lane < 0 ? 1 : -1;  // right-hand traffic: the left lanes run against s
    // Along +s: atan(slope); along -s: pi + atan(slope) (moving -s, t changes by -slope per metre).
    const double expected = direction > 0 ? std::atan(c.slope) : std::numbers::pi + std::atan(c.slope);
    EXPECT_NEAR(wrapped(car.pose.heading - expected), 0.0, 1e-6) << "lane " << c.lane;
    const opendrive::Pose2 before = car.pose;
    advance(car, roads, 0.05, 0.05);
    const double moved = std::atan2(car.pose.y - before.y, car.pose.x - before.x);
    EXPECT_NEAR(wrapped(car.pose.heading - moved), 0.0, 1e-4) << "lane " << c.lane;
    // Standing, it faces along its lane too.
    const EntityState parked = on_lane(roads, c.lane, 100, 0);
    EXPECT_NEAR(wrapped(parked.pose.heading - expected), 0.0, 1e-6) << "lane " << c.lane;
  }
}

TEST(LaneHeading, ALateralActionsRateAddsToTheLanesDrift) {
  const auto roads = opendrive::read_xodr_text(kWideningRoad, "widening.xodr");
  EntityState car = on_lane(roads, -2, 100, 20);
  car.lateral_rate = 1.0;  // leftward, as a lane change to the left
  update_pose(car, roads);
  const double along = std::sqrt(20.0 * 20.0 - 1.0);
  EXPECT_NEAR(car.pose.heading, std::atan2(1.0 - 0.05 * along, along), 1e-6);
}

}  // namespace
}  // namespace orch::openscenario
