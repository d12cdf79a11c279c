// Nurbs trajectory shapes (openscenario/nurbs.hpp), by hand: an order-2 Nurbs is the polyline
// of its control points; the rational quadratic with weights 1, sqrt(2)/2, 1 is an exact
// quarter circle; control point times are linear in u between the peaks of their basis
// functions; shapes the formula cannot take are errors.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "openscenario/nurbs.hpp"

namespace orch::openscenario {
namespace {

TEST(Nurbs, OrderTwoIsThePolylineOfItsControlPoints) {
  // Knots 0 0 1 2 2: u in [0, 1] runs (0,0) -> (10,0), u in [1, 2] runs (10,0) -> (10,10).
  const auto points = nurbs_points({{0, 0, 1, std::nullopt}, {10, 0, 1, std::nullopt}, {10, 10, 1, std::nullopt}},
                                   {0, 0, 1, 2, 2}, 2);
  ASSERT_GE(points.size(), 3u);
  EXPECT_NEAR(points.front().x, 0.0, 1e-12);
  EXPECT_NEAR(points.back().x, 10.0, 1e-6);
  EXPECT_NEAR(points.back().y, 10.0, 1e-6);
  for (const PathPoint& p : points) {
    // on one of the two legs
    const bool first_leg = std::abs(p.y) < 1e-9 && p.x >= -1e-9 && p.x <= 10 + 1e-9;
    const bool second_leg = std::abs(p.x - 10) < 1e-6 && p.y >= -1e-9 && p.y <= 10 + 1e-9;
    EXPECT_TRUE(first_leg || second_leg) << p.x << ", " << p.y;
  }
}

TEST(Nurbs, TheRationalQuadraticWithWeightHalfRootTwoIsAQuarterCircle) {
  const double w = std::sqrt(2.0) / 2;
  const auto points =
      nurbs_points({{10, 0, 1, 0.0}, {10, 10, w, 1.0}, {0, 10, 1, 2.0}}, {0, 0, 0, 1, 1, 1}, 3);
  ASSERT_GT(points.size(), 10u);
  for (const PathPoint& p : points) EXPECT_NEAR(std::hypot(p.x, p.y), 10.0, 1e-9);
  EXPECT_NEAR(points.front().x, 10.0, 1e-12);
  EXPECT_NEAR(points.back().y, 10.0, 1e-6);
  // u = 1/2 (the middle sample): the point at 45 degrees; the middle control point's basis
  // peaks there, so its time 1.0 is due there; the ends at 0 and 2.
  const PathPoint& middle = points[points.size() / 2];
  ASSERT_EQ(points.size() % 2, 1u);
  EXPECT_NEAR(middle.x, 10 * w, 1e-9);
  EXPECT_NEAR(middle.y, 10 * w, 1e-9);
  EXPECT_NEAR(*middle.due, 1.0, 1e-9);
  EXPECT_NEAR(*points.front().due, 0.0, 1e-12);
  EXPECT_NEAR(*points.back().due, 2.0, 1e-6);
  // A quarter of the way in u: halfway between the first peak (u 0) and the second (u 1/2).
  EXPECT_NEAR(*points[(points.size() - 1) / 4].due, 0.5, 0.02);
}

// Control points given with a world z (WorldPositions with z: esmini's parking_demo.xosc
// flies its Camera 10-15 m up) weigh on the height as on x and y; without z, none.
TEST(Nurbs, HeightsAreWeighedAsTheCoordinates) {
  const auto points = nurbs_points({{0, 0, 1, std::nullopt, 10.0}, {10, 0, 1, std::nullopt, 20.0}, {10, 10, 1, std::nullopt, 15.0}},
                                   {0, 0, 1, 2, 2}, 2);
  for (const PathPoint& p : points) {
    ASSERT_TRUE(p.z.has_value());
    const double expected = std::abs(p.y) < 1e-9 ? 10.0 + p.x : 20.0 - p.y / 2;  // linear along each leg
    EXPECT_NEAR(*p.z, expected, 1e-6) << p.x << ", " << p.y;
  }
  EXPECT_NEAR(*points.back().z, 15.0, 1e-6);
  const auto flat = nurbs_points({{0, 0, 1, std::nullopt}, {10, 0, 1, std::nullopt}}, {0, 0, 1, 1}, 2);
  EXPECT_FALSE(flat.front().z.has_value());
}

TEST(Nurbs, ShapesTheFormulaCannotTakeAreErrors) {
  const std::vector<NurbsControl> three{{0, 0, 1, std::nullopt}, {1, 0, 1, std::nullopt}, {2, 0, 1, std::nullopt}};
  EXPECT_THROW((void)nurbs_points(three, {0, 0, 1, 1}, 2), MapError);           // 4 knots, 5 needed
  EXPECT_THROW((void)nurbs_points(three, {0, 0, 0, 0, 1, 1, 1}, 4), MapError);  // fewer points than the order
  EXPECT_THROW((void)nurbs_points(three, {0, 1, 0, 1, 1}, 2), MapError);        // decreasing
  EXPECT_THROW((void)nurbs_points(three, {0, 0, 0, 0, 0}, 2), MapError);        // no span
}

}  // namespace
}  // namespace orch::openscenario
