#include "map/lane_end_crossings.hpp"

#include <cmath>

#include "map/junction_shape.hpp"  // cross2

namespace orch {

namespace {

constexpr double kSameVertex = 0.01;  // m: a lane end this near a corner of the shape is that corner

// Whether segments [a, b] and [c, d] cross or touch.
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 r = b - a;
  const Vec2 q = d - c;
  const double den = r.x() * q.y() - r.y() * q.x();
  if (std::abs(den) < 1e-12) return false;  // parallel: netconvert's test finds no crossing either
  const Vec2 w = c - a;
  const double t = (w.x() * q.y() - w.y() * q.x()) / den;
  const double u = (w.x() * r.y() - w.y() * r.x()) / den;
  return t >= -1e-9 && t <= 1 + 1e-9 && u >= -1e-9 && u <= 1 + 1e-9;
}

// The unit direction of the lane's end segment at its first (last) point, pointing out of
// the lane, over the nearest point at least 1 mm away (netconvert extends that segment).
Vec2 outward(const Polyline& lane, bool at_start) {
  const auto& pts = lane.points();
  const std::size_t n = pts.size();
  const Vec2& end = at_start ? pts.front() : pts.back();
  for (std::size_t k = 1; k < n; ++k) {
    const Vec2& q = at_start ? pts[k] : pts[n - 1 - k];
    if ((end - q).norm() > 1e-3) return (end - q).normalized();
  }
  return Vec2::Zero();
}

}  // namespace

bool far_extension_crosses(const std::vector<Vec2>& shape, const Polyline& lane, bool incoming) {
  if (shape.size() < 2 || lane.size() < 2) return false;
  // The far end: the lane's start when it ends at the junction, else its end.
  const Vec2 dir = outward(lane, incoming);
  if (dir.isZero()) return false;
  const Vec2 a = incoming ? lane.point(0) : lane.points().back();
  // From just beyond the far end (a shape through the far end itself is the other node's business).
  const Vec2 from = a + dir * 1e-3;
  const Vec2 to = a + dir * kNetconvertExtrapolation;
  for (std::size_t k = 0; k < shape.size(); ++k)
    if (segments_meet(from, to, shape[k], shape[(k + 1) % shape.size()])) return true;
  return false;
}

int secure_lane_end_crossings(NetPlan& plan) {
  int changed = 0;
  for (PlannedNode& node : plan.nodes) {
    if (node.shape.size() < 2) continue;
    std::vector<PlannedLane*> lanes;
    std::vector<LaneEnd> ends;  // (pointing at the lanes' shapes, which are changed in place)
    for (PlannedEdge& e : plan.edges)
      for (const bool incoming : {true, false}) {
        if ((incoming ? e.to : e.from) != node.id) continue;
        for (PlannedLane& l : e.lanes) {
          lanes.push_back(&l);
          ends.push_back({&l.shape, incoming});
        }
      }
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      PlannedLane& l = *lanes[i];
      const bool incoming = ends[i].incoming;
      if (!far_extension_crosses(node.shape, l.shape, incoming)) continue;
      const Vec2 into = outward(l.shape, !incoming);  // from the lane end into the junction
      if (into.isZero()) continue;
      const Polyline planned = l.shape;
      std::vector<Vec2> pts = l.shape.points();
      const Vec2 p = incoming ? pts.back() : pts.front();
      if (incoming)
        pts.push_back(p + into * kLaneEndOverlap);
      else
        pts.insert(pts.begin(), p + into * kLaneEndOverlap);
      l.shape = Polyline(std::move(pts));
      // A lane end on a corner of the shape: the corner becomes a bar across the lane,
      // entered from the side of the shape's previous corner and left towards the side of its
      // next one (there and back when both lie on one side), or whichever of those cuts no
      // lane of the junction more than the corner did (a bar's end joined to a far corner
      // may run along the lane it crosses).
      const double cut_before = cut_length(node.shape, ends);
      const Vec2 left = p + Vec2(-into.y(), into.x()) * kLaneEndBarHalf;
      const Vec2 right = p - Vec2(-into.y(), into.x()) * kLaneEndBarHalf;
      const auto on_left = [&](const Vec2& q) { return cross2(p, p + into, q) >= 0; };
      std::vector<Vec2> shape = node.shape;
      bool fits = true;
      for (std::size_t k = 0; k < shape.size() && fits; ++k) {
        if ((shape[k] - p).norm() > kSameVertex) continue;
        const std::size_t n = shape.size();
        const bool from_left = on_left(shape[(k + n - 1) % n]);
        const bool to_left = on_left(shape[(k + 1) % n]);
        const Vec2& a = from_left ? left : right;
        const Vec2& b = from_left ? right : left;
        const std::vector<std::vector<Vec2>> bars =
            from_left == to_left ? std::vector<std::vector<Vec2>>{{a, b, a}, {a, b}, {b, a}, {b, a, b}}
                                 : std::vector<std::vector<Vec2>>{{a, b}, {a, b, a}, {b, a, b}, {b, a}};
        fits = false;
        for (const auto& bar : bars) {
          std::vector<Vec2> trial = shape;
          trial[k] = bar[0];
          trial.insert(trial.begin() + static_cast<std::ptrdiff_t>(k) + 1, bar.begin() + 1, bar.end());
          if (cut_length(trial, ends) <= cut_before + 1e-9) {
            shape = std::move(trial);
            k += bar.size() - 1;
            fits = true;
            break;
          }
        }
      }
      if (!fits) {  // every bar cuts a lane: the lane and the shape stay as planned
        l.shape = planned;
        continue;
      }
      node.shape = std::move(shape);
      ++changed;
    }
  }
  return changed;
}

}  // namespace orch
