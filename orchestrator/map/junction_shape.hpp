#pragma once
// The shape of a SUMO junction that `map build` writes (junction_plan.hpp): netconvert cuts
// every lane of a junction where the junction's shape crosses it (at the crossing farthest
// from the junction, NBEdge::startShapeAt), custom lane shapes included, so the shape must
// touch each lane only at its end. The candidates (a star through the lane ends' corners,
// through their centres, spokes from the middle) and the measure of how much a shape cuts;
// where all of them cut, a tree with no area that cuts none (uncut_tree).
#include <vector>

#include "core/polyline.hpp"

namespace orch {

// m: a junction shape that cuts no more than this off a lane leaves its waypoints within
// `map check`'s tolerance (the shipped urban map's corner shapes cut up to 0.06 m).
inline constexpr double kMaxShapeCut = 0.10;
inline constexpr double kSamePoint = 0.02;  // m: lane ends closer than this meet
// m cut off each of two lanes where one ends on the other's start, so that the internal lane
// joining them has a length (SUMO refuses one of none; more than 0.1 m: `map check`'s floor)
inline constexpr double kEndOnStartCut = 0.08;
// The grid a junction's uncut tree may run through around its lanes (m; at most that many points).
inline constexpr double kTreeGridStep = 1.5;
// m beyond the lane ends the grid reaches, tried in turn while none finds a way round the lanes
inline constexpr double kTreeGridMargins[] = {6.0, 12.0, 24.0, 36.0};
inline constexpr double kTreeGridReach = 1.5 * kTreeGridStep;  // m: grid neighbours, diagonals included
inline constexpr long long kMaxTreeGridPoints = 4000;

// A lane end at a junction: netconvert cuts the lane at the crossing of the junction's shape
// farthest from that end (NBEdge::startShapeAt), so a shape that crosses the lane anywhere
// else than at its end shortens it and leaves waypoints beside no lane.
struct LaneEnd {
  const Polyline* shape = nullptr;
  bool incoming = false;  // the lane ends at the junction (else it starts there)
};

// A point of the junction tree (uncut_tree).
struct TreeNode {
  Vec2 p;
  std::vector<std::size_t> partners;  // corners joined to this one across a lane end
};

double cross2(const Vec2& o, const Vec2& a, const Vec2& b);
// Andrew's monotone chain, counter-clockwise, without collinear points.
std::vector<Vec2> convex_hull(std::vector<Vec2> pts);
// The lane-end corners in the order of their angle around the centre (a polygon touching
// every lane at its end only).
std::vector<Vec2> star_polygon(std::vector<Vec2> corners, const Vec2& centre);
// How far `shape` (a closed polygon) cuts into lane end `e`, m (0 up to kMaxShapeCut).
double cut_into(const std::vector<Vec2>& shape, const LaneEnd& e);
// How much of the lanes `shape` would cut off (m, summed).
double cut_length(const std::vector<Vec2>& shape, const std::vector<LaneEnd>& ends);
// `pts` as a polygon with no area (there and back), so that netconvert closes no other edge.
std::vector<Vec2> there_and_back(std::vector<Vec2> pts);
// A shape with no area through `nodes` (lane ends, corner pairs, the middle) that reaches
// every lane end and crosses none of the lanes: a tree of straight segments between the lane ends (and the junction's middle), each segment chosen
// shortest first among those that cut no lane, walked around (there and back) into the
// polygon netconvert closes. Where a lane ends on the next one's start, the tree runs across
// both lanes between their corners kEndOnStartCut from that point (a vertex on it would give
// netconvert's internal lane between the two no length). Empty when some lane end cannot be
// reached without a cut (the caller keeps the best of its other shapes).
std::vector<Vec2> uncut_tree(std::vector<TreeNode> nodes, const std::vector<LaneEnd>& ends);

}  // namespace orch
