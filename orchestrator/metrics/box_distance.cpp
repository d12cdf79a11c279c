#include "metrics/box_distance.hpp"

#include <algorithm>
#include <limits>

namespace orch::metrics {

namespace {
double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double f = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + f * d)).norm();
}
}  // namespace

double box_distance(const sim::Box& a, const sim::Box& b) {
  if (sim::boxes_touch(a, b)) return 0.0;
  // Two convex polygons apart: the shortest distance joins a corner of one to an edge of
  // the other.
  const auto ca = sim::box_corners(a);
  const auto cb = sim::box_corners(b);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      best = std::min(best, point_segment(ca[i], cb[j], cb[(j + 1) % 4]));
      best = std::min(best, point_segment(cb[i], ca[j], ca[(j + 1) % 4]));
    }
  return best;
}

}  // namespace orch::metrics
