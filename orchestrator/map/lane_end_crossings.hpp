#pragma once
// Makes netconvert cut every lane where `map build` meant it to: at its end, on the junction
// shape. netconvert (NBEdge::startShapeAt) cuts a lane at its farthest direct crossing with
// the junction's shape; a shape that only touches the lane at its end point (every shape of
// junction_shape.hpp does: the lane end lies on it) is a crossing or not by the last digit of
// the plain XML's coordinates. When netconvert sees none, it extends the lane straight by
// 100 m at both ends and cuts at the farthest crossing of that: where the extension beyond
// the lane's *other* end reaches this junction's shape (a dead-end lane curving back beside
// its junction, seeds 449, 459, 503, 510, 765, 892), the "cut" lies beyond the lane's far end,
// the lane points backwards, and netconvert keeps a 0.2 m stub of it.
//
// For such a lane end (only those: every other net keeps its bytes) the lane is extended
// kLaneEndOverlap straight into the junction, so that the shape crosses it there for certain
// and netconvert cuts it back to where it was planned to end. Where the lane end is a corner
// of the shape (an uncut tree's leaf), nothing changes (lane_end_crossings.cpp says why).
#include "map/net_plan.hpp"

namespace orch {

inline constexpr double kLaneEndOverlap = 0.05;  // m: well above the plain XML's 0.1 mm, below kMaxShapeCut
inline constexpr double kNetconvertExtrapolation = 100.0;  // m: NBEdge::startShapeAt's lb.extrapolate2D(100)

// Whether netconvert's straight extension beyond the far end of `lane` (the end away from
// the junction; `incoming`: the lane ends at the junction) crosses the closed `shape`.
bool far_extension_crosses(const std::vector<Vec2>& shape, const Polyline& lane, bool incoming);

// Applies the overlap to every lane end of `plan` at a node whose shape the far extension
// crosses; returns how many lane ends it changed.
int secure_lane_end_crossings(NetPlan& plan);

}  // namespace orch
