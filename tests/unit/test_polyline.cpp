#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
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

namespace {

// project_near as it was before it skipped far segments: every segment of the window
// measured in order, the first of equally near ones kept. Returns the segment, s, distance.
std::tuple<std::size_t, double, double> project_near_by_walk(const Polyline& line, const Vec2& p, double s_hint,
                                                             double window) {
  const auto& pts = line.points();
  std::vector<double> cum(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) cum[i] = cum[i - 1] + (pts[i] - pts[i - 1]).norm();
  auto segment_at = [&](double s) -> std::size_t {
    if (s <= 0) return 0;
    if (s >= cum.back()) return pts.size() - 2;
    const auto seg = static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), s) - cum.begin()) - 1;
    return std::min(seg, pts.size() - 2);
  };
  std::tuple<std::size_t, double, double> best{0, 0.0, std::numeric_limits<double>::infinity()};
  for (std::size_t seg = segment_at(s_hint - window); seg <= segment_at(s_hint + window); ++seg) {
    const Vec2& a = pts[seg];
    const Vec2 d = pts[seg + 1] - a;
    const double len2 = d.squaredNorm();
    const double f = std::clamp(len2 > 0 ? (p - a).dot(d) / len2 : 0.0, 0.0, 1.0);
    const double distance = (p - (a + f * d)).norm();
    if (distance < std::get<2>(best)) best = {seg, cum[seg] + f * std::sqrt(len2), distance};
  }
  return best;
}

}  // namespace

// The pruned search gives the walk's answer bit for bit: straight 1 m lines far from the
// origin (rounding), arcs, zigzags whose vertices tie, repeated points (zero-length
// segments); points on, beside and far from the line, hints off by up to the window.
TEST(Polyline, ProjectNearMatchesTheWalkOverTheWholeWindow) {
  std::mt19937 rng(28);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int shape = 0; shape < 40; ++shape) {
    std::vector<Vec2> pts;
    const Vec2 origin(u(rng) * 2e4, u(rng) * 2e4);
    const int n = 50 + static_cast<int>(u(rng) * 3000);
    for (int i = 0; i <= n; ++i) {
      Vec2 q;
      switch (shape % 4) {
        case 0: q = Vec2(i, 0.001 * i); break;                                           // straight, 1 m
        case 1: q = 200.0 * Vec2(std::cos(i * 0.004), std::sin(i * 0.004)); break;      // arc
        case 2: q = Vec2(i, (i % 2) * 1.5); break;                                       // zigzag: vertex ties
        default: q = pts.empty() ? Vec2(0, 0) : pts.back() - origin + Vec2(u(rng) < 0.2 ? 0.0 : u(rng) * 3, u(rng) - 0.5);
      }
      pts.push_back(origin + q);
    }
    const Polyline line(pts);
    for (int k = 0; k < 200; ++k) {
      const double window = k % 5 == 0 ? 1e6 : 1 + u(rng) * 80;
      const double s_true = u(rng) * line.length();
      const double s_hint = s_true + (u(rng) - 0.5) * 2 * window;
      const double off = k % 7 == 0 ? u(rng) * 500 : (u(rng) - 0.5) * 8;
      const Vec2 at = line.point_at(s_true) + Vec2(u(rng) - 0.5, off);
      const auto r = line.project_near(at, s_hint, window);
      const auto [segment, s, distance] = project_near_by_walk(line, at, s_hint, window);
      ASSERT_EQ(r.segment, segment) << "shape " << shape << " point " << k;
      ASSERT_EQ(r.s, s) << "shape " << shape << " point " << k;
      ASSERT_EQ(r.distance, distance) << "shape " << shape << " point " << k;
    }
  }
}
