#include "sim/box.hpp"

#include <algorithm>
#include <cmath>

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

}  // namespace orch::sim
