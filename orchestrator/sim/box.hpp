#pragma once
// A body as an oriented rectangle (centre, heading, length, width), and the exact test of
// two touching: what the collision monitors of both scenario languages and the metrics use.
#include <array>

#include "core/polyline.hpp"

namespace orch::sim {

struct Box {
  Vec2 centre{0, 0};
  double heading = 0;
  double length = 0;
  double width = 0;
};

// True when the two rectangles share any point (touching edges count).
bool boxes_touch(const Box& a, const Box& b);
// The four corners, front-left, front-right, rear-right, rear-left.
std::array<Vec2, 4> box_corners(const Box& b);
// The shortest distance between the two rectangles, 0 when they touch (the metrics' minimum
// distance, docs/evaluation.md; OpenSCENARIO's freespace distance between bounding boxes).
double box_distance(const Box& a, const Box& b);

}  // namespace orch::sim
