#include "openscenario/entity_measures.hpp"

#include <algorithm>
#include <cmath>

namespace orch::openscenario {
namespace {

// The gap between two boxes along one axis, given the signed distance `d` of `to`'s
// reference point from `from`'s and each box's extent [low, high] along that axis.
double gap(double d, double from_low, double from_high, double to_low, double to_high) {
  if (d >= 0) return std::max(0.0, d + to_low - from_high);
  return std::max(0.0, -d - to_high + from_low);
}

}  // namespace

double relative_distance(const Body& from, const Body& to, const std::string& distance_type,
                         const std::string& coordinate_system, bool freespace) {
  double along = 0;
  double across = 0;
  if (coordinate_system == "entity") {
    const double dx = to.state->pose.x - from.state->pose.x;
    const double dy = to.state->pose.y - from.state->pose.y;
    const double h = from.state->pose.heading;
    along = dx * std::cos(h) + dy * std::sin(h);
    across = -dx * std::sin(h) + dy * std::cos(h);
  } else {  // road / lane: differences of s and of t on the shared road
    along = to.state->s - from.state->s;
    across = to.state->t - from.state->t;
  }
  if (freespace) {
    const BoundingBox& a = *from.box;
    const BoundingBox& b = *to.box;
    along = gap(along, a.center_x - a.length / 2, a.center_x + a.length / 2, b.center_x - b.length / 2,
                b.center_x + b.length / 2);
    across = gap(across, a.center_y - a.width / 2, a.center_y + a.width / 2, b.center_y - b.width / 2,
                 b.center_y + b.width / 2);
  }
  if (distance_type == "longitudinal") return std::abs(along);
  if (distance_type == "lateral") return std::abs(across);
  return std::hypot(along, across);
}

}  // namespace orch::openscenario
