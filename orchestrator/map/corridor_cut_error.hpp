#pragma once
// The corridor planner's refusal to cut a line consistently with its neighbours
// (net_plan.cpp). plan_net catches it to name the drawn route's waypoint there: on junction
// maps the line is a piece of a route between two junctions ("Loop15.0"), which a user never
// drew.
#include <cstddef>
#include <string>

#include "core/errors.hpp"
#include "core/polyline.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

class CorridorCutError : public MapError {
 public:
  CorridorCutError(const std::string& message, std::size_t line, const Vec2& point)
      : MapError(message), line_(line), point_(point) {}
  [[nodiscard]] std::size_t line() const { return line_; }  // index into plan_corridors' `lines`
  [[nodiscard]] const Vec2& point() const { return point_; }

 private:
  std::size_t line_;
  Vec2 point_;
};

// The index of the waypoint of `route` nearest to p.
inline std::size_t nearest_waypoint(const WaypointRoute& route, const Vec2& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < route.line.size(); ++i)
    if ((route.line.point(i) - p).norm() < (route.line.point(best) - p).norm()) best = i;
  return best;
}

// The refusal with the drawn route's waypoint named (`route`: the route the line was cut from).
inline MapError name_waypoint(const CorridorCutError& e, const WaypointRoute& route) {
  const std::size_t wp = nearest_waypoint(route, e.point());
  return MapError(std::string(e.what()) + " (route \"" + route.id + "\" wp_idx " + std::to_string(wp) + ")");
}

}  // namespace orch
