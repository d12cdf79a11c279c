#include "scenario_executor_engine/lane_change_conflicts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace orch::engine {

void LaneChangeConflicts::watch(ActorId actor, double length, const WaypointRoute& target, int direction,
                                double lane_width, double until) {
  std::erase_if(watches_, [&](const Watch& w) { return w.actor == actor; });
  Watch w;
  w.actor = actor;
  w.length = length;
  w.target = &target;
  w.direction = direction;
  w.half_width = lane_width / 2;
  w.until = until;
  w.s_hint = -1;
  watches_.push_back(std::move(w));
}

std::vector<LaneChangeConflict> LaneChangeConflicts::step(const WorldSnapshot& snap) {
  std::vector<LaneChangeConflict> found;
  // A lane change is watched through the step in which it completes.
  std::erase_if(watches_, [&](const Watch& w) { return snap.time > w.until + 1e-9; });
  for (Watch& w : watches_) {
    const ActorState* a = snap.find(w.actor);
    if (!a || !a->present) continue;
    const Polyline& line = w.target->line;
    const auto pa = w.s_hint < 0 ? line.project(a->position) : line.project_near(a->position, w.s_hint, 100.0);
    w.s_hint = pa.s;
    const double travel_heading = w.direction > 0 ? line.heading_at(pa.s) : wrap_angle(line.heading_at(pa.s) + std::numbers::pi);
    for (const NearbyVehicle& v : snap.nearby) {
      if (w.reported.count(v.sumo_id)) continue;
      if (std::cos(wrap_angle(v.heading - travel_heading)) < 0.5) continue;  // other direction or crossing
      const auto pv = line.project_near(v.position, pa.s, 100.0);
      if (pv.before_start || pv.after_end || std::abs(pv.lateral) > w.half_width) continue;
      const double ahead = w.direction * (pv.s - pa.s);  // + = the vehicle is ahead of the actor
      const double gap = std::max(0.0, std::abs(ahead) - (w.length + v.length) / 2);
      const double behind_speed = ahead >= 0 ? a->speed : v.speed;
      const double time_gap = behind_speed > 1e-6 ? gap / behind_speed : std::numeric_limits<double>::infinity();
      if (gap >= kMinGap && time_gap >= kMinTimeGap) continue;
      w.reported.insert(v.sumo_id);
      LaneChangeConflict c{snap.time, w.actor, v.sumo_id, w.target->id, gap, ahead >= 0, time_gap,
                           a->position, v.position};
      found.push_back(c);
      all_.push_back(std::move(c));
    }
  }
  return found;
}

}  // namespace orch::engine
