#include "sim/box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace orch::sim {

namespace {

// Separating-axis test: two convex shapes are apart exactly when their projections onto
// one of the shapes' edge normals do not overlap.
bool separated_on(const Vec2& axis, const std::array<Vec2, 4>& a, const std::array<Vec2, 4>& b) {
  double amin = a[0].dot(axis), amax = amin, bmin = b[0].dot(axis), bmax = bmin;
  for (int i = 1; i < 4; ++i) {
    amin = std::min(amin, a[i].dot(axis));
    amax = std::max(amax, a[i].dot(axis));
    bmin = std::min(bmin, b[i].dot(axis));
    bmax = std::max(bmax, b[i].dot(axis));
  }
  return amax < bmin || bmax < amin;
}

}  // namespace

std::array<Vec2, 4> box_corners(const Box& b) {
  const Vec2 f(std::cos(b.heading), std::sin(b.heading));
  const Vec2 l(-f.y(), f.x());
  const Vec2 hf = f * (b.length / 2);
  const Vec2 hl = l * (b.width / 2);
  return {b.centre + hf + hl, b.centre + hf - hl, b.centre - hf - hl, b.centre - hf + hl};
}

bool boxes_touch(const Box& a, const Box& b) {
  // Far apart: no need for the corner arithmetic.
  const double reach = (std::hypot(a.length, a.width) + std::hypot(b.length, b.width)) / 2;
  if ((a.centre - b.centre).squaredNorm() > reach * reach) return false;
  const auto ca = box_corners(a);
  const auto cb = box_corners(b);
  for (const Box* box : {&a, &b}) {
    const Vec2 f(std::cos(box->heading), std::sin(box->heading));
    if (separated_on(f, ca, cb) || separated_on(Vec2(-f.y(), f.x()), ca, cb)) return false;
  }
  return true;
}

namespace {
double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double f = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + f * d)).norm();
}
}  // namespace

double box_distance(const sim::Box& a, const sim::Box& b) {
  if (boxes_touch(a, b)) return 0.0;
  // Two convex polygons apart: the shortest distance joins a corner of one to an edge of
  // the other.
  const auto ca = box_corners(a);
  const auto cb = box_corners(b);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      best = std::min(best, point_segment(ca[i], cb[j], cb[(j + 1) % 4]));
      best = std::min(best, point_segment(cb[i], ca[j], ca[(j + 1) % 4]));
    }
  return best;
}

}  // namespace orch::sim
