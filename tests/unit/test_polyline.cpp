#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/polyline.hpp"

using orch::Polyline;
using orch::Vec2;

namespace {
Polyline quarter_circle(double radius, int n) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= n; ++i) {
    const double a = std::numbers::pi / 2 * i / n;
    pts.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return Polyline(pts);
}
}  // namespace

TEST(Polyline, ArcLengthAndPointAt) {
  Polyline p({{0, 0}, {10, 0}, {10, 10}});
  EXPECT_DOUBLE_EQ(p.length(), 20.0);
  EXPECT_TRUE(p.point_at(15).isApprox(Vec2(10, 5)));
  // Beyond the ends the end segments are extended straight.
  EXPECT_TRUE(p.point_at(-2).isApprox(Vec2(-2, 0)));
  EXPECT_TRUE(p.point_at(23).isApprox(Vec2(10, 13)));
}

TEST(Polyline, FractionalIndexInterpolates) {
  Polyline p({{0, 0}, {1, 0}, {3, 0}});
  EXPECT_DOUBLE_EQ(p.s_at_fractional_index(1.5), 2.0);
  EXPECT_DOUBLE_EQ(p.s_at_fractional_index(99), 3.0);
}

TEST(Polyline, ProjectionSignsLeftPositive) {
  Polyline p({{0, 0}, {100, 0}});
  const auto left = p.project({40, 3});
  EXPECT_NEAR(left.s, 40, 1e-9);
  EXPECT_NEAR(left.lateral, 3, 1e-9);
  const auto right = p.project({40, -2});
  EXPECT_NEAR(right.lateral, -2, 1e-9);
  const auto beyond = p.project({105, 0});
  EXPECT_TRUE(beyond.after_end);
  EXPECT_FALSE(left.after_end);
}

TEST(Polyline, ProjectionOnLongRouteFindsTheNearestSegment) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= 10000; ++i) pts.emplace_back(i, 0.001 * i);
  Polyline p(pts);
  const auto r = p.project({7321.4, 12.0});
  EXPECT_NEAR(r.s, 7321.4 * std::sqrt(1 + 1e-6) + 12.0 * 0.001, 0.05);
  // Far from the line the grid search falls back to a full scan and still finds it.
  const auto far = p.project({5000, 900});
  EXPECT_NEAR(far.distance, 900 - 5.0, 1.0);
}

TEST(Polyline, SimplifyKeepsEveryPointWithinTolerance) {
  Polyline arc = quarter_circle(100, 400);
  Polyline simple = arc.simplified(0.02);
  EXPECT_LT(simple.size(), arc.size());
  for (const auto& pt : arc.points()) EXPECT_LE(simple.project(pt).distance, 0.02 + 1e-9);
}

TEST(Polyline, SliceCutsExactly) {
  Polyline p({{0, 0}, {10, 0}, {20, 0}});
  Polyline s = p.slice(5, 15);
  EXPECT_DOUBLE_EQ(s.length(), 10.0);
  EXPECT_TRUE(s.point(0).isApprox(Vec2(5, 0)));
}
