#pragma once
// The distance between two bodies (docs/evaluation.md "Minimum distance"): the shortest
// distance between their oriented rectangles, the collision test's geometry
// (engine/collision.hpp); 0 when they touch.
#include "sim/box.hpp"

namespace orch::metrics {

double box_distance(const sim::Box& a, const sim::Box& b);

}  // namespace orch::metrics
