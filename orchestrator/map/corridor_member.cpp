#include "map/corridor_member.hpp"

#include <fmt/format.h>

namespace orch::corridor {

double lane_speed(const Member& m, double s0, double s1, std::vector<std::string>& notes) {
  const WaypointRoute& r = *m.route;
  double best = 0;
  bool any = false;
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const double s = m.first_wp_s + r.line.s_at_index(i);
    if (s < s0 || s > s1) continue;
    best = std::max(best, r.points[i].v);
    any = true;
  }
  // A stretch that lies wholly in the straight extension takes the speed of the end it extends.
  if (!any) best = (s1 <= m.first_wp_s) ? r.points.front().v : r.points.back().v;
  if (best > 0) return best;
  notes.push_back(fmt::format("route \"{}\" has no positive target speed v between its waypoints; its lane gets "
                              "{:.2f} m/s", r.id, kFallbackLaneSpeed));
  return kFallbackLaneSpeed;
}

}  // namespace orch::corridor
