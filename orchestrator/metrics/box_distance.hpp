#pragma once
// The distance between two bodies (docs/evaluation.md "Minimum distance"): the shortest
// distance between their oriented rectangles, the collision test's geometry
// (engine/collision.hpp); 0 when they touch.
#include "engine/collision.hpp"

namespace orch::metrics {

double box_distance(const engine::Box& a, const engine::Box& b);

}  // namespace orch::metrics
