#pragma once
// When SUMO's map matching has only one answer. moveToXY with keepRoute 2 (free placement)
// weighs every lane of every edge near the point (their whole shapes, each step: on a map of
// long curved roads most of a run's time); with keepRoute 3 it looks only at the lanes of the
// vehicle's route and takes the hinted lane when the point lies on it. Both put the vehicle on
// the hinted lane, at the same position and lateral offset, when its front lies well inside
// that lane: nearer its centre line than a quarter of its width (so nearer than any other lane
// of the edge, whose centre is at least half a width away) and its nearest point inside the
// shape (not at an end, where SUMO calls the match ambiguous and looks elsewhere). The free
// match scores each lane by 0.5 (1 - d / M) (d its distance, M the largest of the candidates'
// distances, capped at 3.2 m), 0.35 for the angle, 1 for the hinted lane and at most 0.2 for
// route and edge: the hinted lane wins whenever d_hint / M < 0.9. Another lane of the edge
// that the vehicle may use, at least w/4 + (its width)/2 away, makes that so; without one the
// vehicle must also head along the lane (within 90 degrees: then d_hint / M <= 1 suffices,
// and the hinted lane is a candidate itself). Pure geometry, so that it can be tested without SUMO;
// sumo_placement.hpp asks SUMO for the shapes.
#include <cmath>
#include <optional>

#include "core/polyline.hpp"

namespace orch {

// Metres kept from either end of the lane's shape: SUMO extends a lane by 0.1 m
// (POSITION_EPS) when it decides whether a point lies beside it or beyond its end.
constexpr double kLaneFitEndMargin = 0.5;

// Whether a vehicle front at `front` heading `heading` (radians, counter-clockwise from +x)
// lies well inside the lane of centre line `shape` and width `width` (see above);
// `edge_lanes` is the number of lanes of the lane's edge that the vehicle's class may use
// (SUMO's free match weighs no others).
inline bool front_fits_lane(const Polyline& shape, double width, int edge_lanes, const Vec2& front,
                            double heading) {
  if (shape.empty() || !(width > 0) || !std::isfinite(front.x()) || !std::isfinite(front.y())) return false;
  if (shape.length() <= 2 * kLaneFitEndMargin) return false;
  const std::optional<Polyline::Projection> p = shape.project_within(front, width / 4);
  if (!p || p->before_start || p->after_end) return false;
  if (p->s < kLaneFitEndMargin || p->s > shape.length() - kLaneFitEndMargin) return false;
  if (edge_lanes > 1) return true;
  const Vec2 along = shape.tangent_at(p->s);
  return along.dot(Vec2(std::cos(heading), std::sin(heading))) > 0;
}

}  // namespace orch
