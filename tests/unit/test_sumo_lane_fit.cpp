// When a scripted vehicle's front lies so well inside its hinted lane that SUMO's free map
// matching and the matching along its route must agree (adapters/sumo/lane_fit.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sumo/lane_fit.hpp"

using orch::front_fits_lane;
using orch::Polyline;
using orch::Vec2;

namespace {

// A lane going east along y = 0 from x = 0 to x = 100, 3.2 m wide.
Polyline straight() { return Polyline({Vec2(0, 0), Vec2(50, 0), Vec2(100, 0)}); }

// A counter-clockwise arc of radius 50 m around the origin, 1 degree per point.
Polyline arc() {
  std::vector<Vec2> pts;
  for (int i = 0; i <= 90; ++i) {
    const double a = i * std::numbers::pi / 180;
    pts.emplace_back(50 * std::cos(a), 50 * std::sin(a));
  }
  return Polyline(pts);
}

}  // namespace

TEST(SumoLaneFit, FrontOnTheCentreLineFits) {
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 1, Vec2(40, 0), 0.0));
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 1, Vec2(40, 0.79), 0.1));
}

TEST(SumoLaneFit, MoreThanAQuarterOfTheWidthAwayDoesNotFit) {
  // 0.8 m is a quarter of 3.2 m: nearer than that, no other lane of the edge can be nearer.
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 1, Vec2(40, -0.79), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(40, -0.81), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(40, 1.6), 0.0));
}

TEST(SumoLaneFit, NearEitherEndDoesNotFit) {
  // SUMO calls a point beyond (or at) a lane's end ambiguous and matches it elsewhere.
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(0.2, 0), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(-0.3, 0), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(99.7, 0), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(100.4, 0), 0.0));
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 1, Vec2(0.6, 0), 0.0));
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 1, Vec2(99.4, 0), 0.0));
}

TEST(SumoLaneFit, HeadingAgainstTheLaneOfASingleLaneEdgeDoesNotFit) {
  // SUMO's free match weighs the angle: with no other lane of the edge to bound the distance
  // scale, a vehicle facing backwards could go to another edge's lane.
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(40, 0), std::numbers::pi));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(40, 0), std::numbers::pi / 2 + 0.01));
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 1, Vec2(40, 0), std::numbers::pi / 2 - 0.01));
}

TEST(SumoLaneFit, AnyHeadingFitsALaneWithNeighbours) {
  // Another lane of the edge keeps the hinted lane's bonus ahead of any angle (a cone placed
  // facing against its lane).
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 2, Vec2(40, 0.5), std::numbers::pi));
  EXPECT_TRUE(front_fits_lane(straight(), 3.2, 4, Vec2(40, 0), -std::numbers::pi / 2));
  // The other conditions still hold.
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 2, Vec2(40, 0.9), std::numbers::pi));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 2, Vec2(99.8, 0), std::numbers::pi));
}

TEST(SumoLaneFit, FollowsACurvedLane) {
  const Polyline lane = arc();
  for (int deg = 5; deg <= 85; deg += 10) {
    const double a = deg * std::numbers::pi / 180;
    const double along = a + std::numbers::pi / 2;  // counter-clockwise travel
    EXPECT_TRUE(front_fits_lane(lane, 3.5, 1, Vec2(50.5 * std::cos(a), 50.5 * std::sin(a)), along)) << deg;
    EXPECT_FALSE(front_fits_lane(lane, 3.5, 1, Vec2(51 * std::cos(a), 51 * std::sin(a)), along)) << deg;
    EXPECT_FALSE(front_fits_lane(lane, 3.5, 1, Vec2(50 * std::cos(a), 50 * std::sin(a)), along + std::numbers::pi)) << deg;
  }
}

TEST(SumoLaneFit, DegenerateInputDoesNotFit) {
  EXPECT_FALSE(front_fits_lane(Polyline(), 3.2, 1, Vec2(0, 0), 0.0));
  EXPECT_FALSE(front_fits_lane(Polyline({Vec2(0, 0), Vec2(0.8, 0)}), 3.2, 1, Vec2(0.4, 0), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 0.0, 1, Vec2(40, 0), 0.0));
  EXPECT_FALSE(front_fits_lane(straight(), 3.2, 1, Vec2(std::nan(""), 0), 0.0));
}
