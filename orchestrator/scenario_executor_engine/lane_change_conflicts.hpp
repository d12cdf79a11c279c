#pragma once
// Background traffic in the way of a scripted lane change. The scripted actor changes lanes
// exactly as the scenario says (the scenario's business); what the test engineer needs to
// know is that a SUMO vehicle was in the target lane too close to make room, so the run's
// outcome can be read with that in mind. Recorded once per lane change and vehicle, in the
// run log and result.json (`lane_change_conflicts`); a contact is a collision as any other.
//
// A background vehicle is in conflict when, during the lane change, it drives in the
// target lane (centre within half a lane width of the target route, heading within 60 deg)
// and the bumper-to-bumper gap to the actor is under kMinGap or under kMinTimeGap seconds
// at the speed of whichever of the two is behind.
#include <set>
#include <string>
#include <vector>

#include "core/polyline.hpp"
#include "scenario_executor_engine/sim_names.hpp"
#include "map/waypoint_file.hpp"

namespace orch::engine {

struct LaneChangeConflict {
  double time = 0;
  ActorId actor = 0;
  std::string vehicle;       // SUMO id of the background vehicle
  std::string target_route;  // the waypoint route the actor changes to
  double gap = 0;            // m, bumper to bumper along the target route (0 = side by side)
  bool vehicle_ahead = false;
  double time_gap = 0;       // s, gap / speed of the one behind (infinite at speed 0)
  Vec2 actor_position{0, 0};
  Vec2 vehicle_position{0, 0};
};

class LaneChangeConflicts {
 public:
  static constexpr double kMinGap = 2.0;      // m
  static constexpr double kMinTimeGap = 1.0;  // s

  // The actor (of this length) changes to `target` between now and `until`; the target
  // lane is `lane_width` wide; direction -1 when the actor drives against the route as drawn.
  // A new lane change of the same actor replaces its watch.
  void watch(ActorId actor, double length, const WaypointRoute& target, int direction, double lane_width,
             double until);

  // Checks the watched lane changes against the snapshot's nearby vehicles; returns the
  // conflicts that began in this step (also kept in all()).
  std::vector<LaneChangeConflict> step(const WorldSnapshot& snap);

  [[nodiscard]] const std::vector<LaneChangeConflict>& all() const { return all_; }

 private:
  struct Watch {
    ActorId actor = 0;
    double length = 0;
    const WaypointRoute* target = nullptr;
    int direction = 1;
    double half_width = 0;
    double until = 0;
    double s_hint = 0;
    std::set<std::string> reported;
  };
  std::vector<Watch> watches_;
  std::vector<LaneChangeConflict> all_;
};

}  // namespace orch::engine
