#include "scenario_executor_engine/route_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace orch::engine {

namespace {

constexpr double kMeetDistance = 0.5;  // m: a point of the other route this close is on the route
constexpr double kBeside = 4.0;        // m: a target this close to the route is on or beside it
constexpr double kAlignedCos = 0.7;    // ... and heading its way (within 45 degrees)

}  // namespace

std::vector<RouteMeeting> route_meetings(const WaypointRoute& route, const WaypointRoute& other) {
  std::vector<RouteMeeting> out;
  bool inside = false;
  for (std::size_t i = 0; i < other.line.size(); ++i) {
    const Polyline::Projection p = route.line.project(other.line.point(i));
    const bool on = p.distance < kMeetDistance && !p.before_start && !p.after_end;
    if (on && !inside) out.push_back({p.s, other.line.s_at_index(i)});
    inside = on;
  }
  return out;
}

const std::vector<RouteMeeting>& RouteMeetings::between(const WaypointRoute& route, const WaypointRoute& other) {
  const auto key = std::make_pair(&route, &other);
  auto it = cache_.find(key);
  if (it == cache_.end()) it = cache_.emplace(key, route_meetings(route, other)).first;
  return it->second;
}

std::optional<double> conflict_point_gap(const WaypointRoute& route, const Vec2& actor, const WaypointRoute& other,
                                         const Vec2& target, RouteMeetings& meetings) {
  if (&route == &other) return std::nullopt;
  const Polyline::Projection on_route = route.line.project(target);
  const Polyline::Projection on_other = other.line.project(target);
  const bool aligned = std::abs(route.line.tangent_at(on_route.s).dot(other.line.tangent_at(on_other.s))) >= kAlignedCos;
  if (on_route.distance <= kBeside && aligned && !on_route.before_start && !on_route.after_end) return std::nullopt;
  const auto& list = meetings.between(route, other);
  if (list.empty()) return std::nullopt;
  const double s_actor = route.line.project(actor).s;
  const double s_target = on_other.s;
  double best = std::numeric_limits<double>::infinity();
  double gap = 0;
  for (const RouteMeeting& m : list) {
    const double d_actor = m.s_route - s_actor;
    const double d_target = m.s_other - s_target;
    const double far = std::max(std::abs(d_actor), std::abs(d_target));
    if (far < best) {
      best = far;
      gap = d_actor - d_target;
    }
  }
  return gap;
}

}  // namespace orch::engine
