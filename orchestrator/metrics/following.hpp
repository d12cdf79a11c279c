#pragma once
// Leader and follower along an actor's own route, and the car-following measures towards
// them (docs/evaluation.md "Following"). Pure functions: the route is the polyline the
// actor drives (its waypoint route, across edge and junction boundaries), the bodies are
// what the snapshot holds.
//
// Conventions:
//   s           arc length along the route, counted in the actor's direction of travel;
//   gap         bumper to bumper along the road, m: |s_other - s_self| - (L_self + L_other)/2,
//               never below 0;
//   rel_speed   closing speed, m/s: the speed along the road of the one behind minus the one
//               ahead's (+ = closing in);
//   ttc         gap / rel_speed while closing (rel_speed > 0), else none;
//   thw         gap / speed along the road of the one behind (> 0), else none;
//   drac        rel_speed^2 / (2 gap) while closing and gap > 0, else none.
// A body is on the actor's path when the two bodies overlap sideways on the route:
// |lateral_other - lateral_self| < (W_self + W_other)/2; only bodies within kFollowingRange
// along the road count.
#include <optional>
#include <string>
#include <vector>

#include "core/polyline.hpp"

namespace orch::metrics {

inline constexpr double kFollowingRange = 250.0;  // m along the road

struct Body {
  std::string id;  // actor id ("3") or SUMO id of a background vehicle
  Vec2 centre{0, 0};
  double heading = 0;  // rad, counter-clockwise from +x
  double speed = 0;    // m/s, along the heading
  double length = 0;
  double width = 0;
};

struct Following {
  std::string other;  // the leader's (or follower's) id
  double gap = 0;
  double rel_speed = 0;
  std::optional<double> ttc;
  std::optional<double> thw;
  std::optional<double> drac;
};

// The measures for a body `behind` following one `ahead` at `gap` m; speeds along the road.
Following following_measures(std::string other, double gap, double speed_behind, double speed_ahead);

struct Neighbours {
  std::optional<Following> leader;
  std::optional<Following> follower;
};

// The nearest body ahead of and behind `self` on its path along `route`.
Neighbours find_neighbours(const Polyline& route, const Body& self, const std::vector<Body>& others);

}  // namespace orch::metrics
