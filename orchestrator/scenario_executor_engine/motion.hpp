#pragma once
// Kinematics of one scripted actor: where the scenario says it is, step by step. No SUMO
// driver model is involved: SUMO is told the resulting pose each step.
//
// Vehicles follow a waypoint route: arc length s along the route line, a lateral offset
// (+ = left of the direction of travel), and a direction of travel (+1 along the route as
// drawn, -1 against it, after a lane change into a lane of the opposite side). A pedestrian
// doing a waypoint route_move walks straight lines instead.
#include <optional>
#include <vector>

#include "core/polyline.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/model.hpp"

namespace orch::engine {

// A smooth lateral move: position, velocity and acceleration are continuous at both ends
// (quintic "smootherstep"), as a driver's steering produces.
struct LateralMove {
  double from = 0;
  double to = 0;
  double start = 0;     // s of simulation time
  double duration = 0;  // s; 0 = instant
  [[nodiscard]] double value_at(double t) const;
  [[nodiscard]] double rate_at(double t) const;  // m/s
  [[nodiscard]] bool done_at(double t) const { return t >= start + duration - 1e-9; }
};

// One leg of a queued lateral plan (route_move wp_offset legs run in order).
struct LateralLeg {
  double to = 0;
  double duration = 0;
};

// One leg of a vehicle's waypoint route_move: reach `lateral` metres beside arc length `s`
// of `route` after `duration` seconds, at constant speed along the road.
struct RouteLegTarget {
  const WaypointRoute* route = nullptr;
  double s = 0;
  double lateral = 0;  // + = left of the route as drawn
  double duration = 0;
};

class ScriptedMotion {
 public:
  ScriptedMotion(const WaypointRoute& route, double s, double lateral, double speed,
                 double heading_offset, double length, double lane_extension);

  // ---- longitudinal: the speed the actor heads for; accel <= 0 means instantly.
  void set_desired(double speed, double accel) {
    desired_speed_ = speed;
    desired_accel_ = accel;
  }
  // ---- lateral
  // Replace any lateral plan by these legs, starting at time t from the current offset.
  void plan_lateral(const std::vector<LateralLeg>& legs, double t);
  // Move onto another route (a lane change): continue from the point of the new route
  // nearest to the actor, in the same direction of travel (against the route as drawn if
  // it runs the other way), drifting onto its line plus `target_offset` over `duration`.
  void change_route(const WaypointRoute& route, double target_offset, double t, double duration);
  // ---- a vehicle's waypoint route_move: legs along the road, in order. Replaces the
  // lateral plan; longitudinal wishes are ignored until the last leg ends.
  void plan_route_legs(const std::vector<RouteLegTarget>& legs, double t);
  // ---- free walking (a pedestrian's waypoint route_move): straight lines, in order.
  void plan_walk(const std::vector<std::pair<Vec2, double>>& legs, double t);
  // Stop any route_move (walk or route legs) where the actor is now.
  void cancel_moves();

  // Advances the state from t to t + dt.
  void advance(double t, double dt);

  [[nodiscard]] const WaypointRoute& route() const { return *route_; }
  [[nodiscard]] double s() const { return s_; }
  [[nodiscard]] int direction() const { return direction_; }
  // Offset from the route line, + = left of the route as drawn (what lane lookups need).
  [[nodiscard]] double route_lateral() const { return direction_ * lateral_; }
  [[nodiscard]] double lateral() const { return lateral_; }  // + = left of travel
  [[nodiscard]] double speed() const { return speed_; }
  [[nodiscard]] double accel() const { return accel_; }
  [[nodiscard]] Vec2 position() const;
  [[nodiscard]] double heading() const;
  [[nodiscard]] bool lateral_busy() const { return active_lateral_.has_value() || !pending_lateral_.empty(); }
  [[nodiscard]] bool at_route_end() const { return at_end_; }
  // True once the actor brakes because its lane ends ahead (reported once by the engine).
  [[nodiscard]] bool running_out_of_road() const { return running_out_; }
  [[nodiscard]] bool walking() const { return free_position_.has_value(); }
  [[nodiscard]] bool on_route_legs() const { return route_leg_.has_value() || !pending_route_legs_.empty(); }

  static constexpr double kEndOfLaneDecel = 3.0;  // m/s^2

 private:
  struct ActiveRouteLeg {
    double start_s, end_s, start_time, duration;
  };
  struct WalkLeg {
    Vec2 from, to;
    double start, duration;
  };

  void advance_longitudinal(double dt);
  void advance_route_leg(double t_next, double dt);
  void advance_lateral(double t_next, double dt);
  void advance_walk(double t, double dt);
  void start_route_leg(const RouteLegTarget& leg, double t);
  void switch_route(const WaypointRoute& route);
  [[nodiscard]] double s_max() const;
  [[nodiscard]] double s_min() const;
  [[nodiscard]] double room_ahead() const;

  const WaypointRoute* route_;
  int direction_ = 1;
  double s_;
  double lateral_;
  double lateral_rate_ = 0;
  double speed_;
  double accel_ = 0;
  double heading_offset_;
  double length_;
  double lane_extension_;
  double desired_speed_;
  double desired_accel_ = 0;
  bool at_end_ = false;
  bool running_out_ = false;

  std::optional<LateralMove> active_lateral_;
  std::vector<LateralLeg> pending_lateral_;  // back() runs next

  std::optional<ActiveRouteLeg> route_leg_;
  std::vector<RouteLegTarget> pending_route_legs_;  // back() runs next

  std::optional<WalkLeg> walk_active_;
  std::vector<std::pair<Vec2, double>> walk_pending_;  // back() runs next
  std::optional<Vec2> free_position_;  // set once the actor has walked off its route line
  double free_heading_ = 0;
};

}  // namespace orch::engine
