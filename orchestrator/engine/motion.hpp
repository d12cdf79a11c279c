#pragma once
// Kinematics of one scripted actor: where the scenario says it is, step by step. Vehicles
// follow a waypoint route (arc length s, lateral offset from the route line); a pedestrian
// doing a waypoint route_move walks straight lines. No SUMO driver model is involved:
// SUMO is told the resulting pose each step.
#include <optional>
#include <vector>

#include "core/polyline.hpp"
#include "map/waypoint_file.hpp"
#include "scenario/model.hpp"

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
  // nearest to the actor, drifting from the current lateral distance to the new route's
  // line (offset `target_offset`) over `duration`.
  void change_route(const WaypointRoute& route, double target_offset, double t, double duration);
  // ---- free walking (pedestrian route_move of type waypoint): straight line to `target`
  // arriving after `duration`; a queue of such legs runs in order.
  void plan_walk(const std::vector<std::pair<Vec2, double>>& legs, double t);

  // Advances the state from t to t + dt.
  void advance(double t, double dt);

  [[nodiscard]] const WaypointRoute& route() const { return *route_; }
  [[nodiscard]] double s() const { return s_; }
  [[nodiscard]] double lateral() const { return lateral_; }
  [[nodiscard]] double speed() const { return speed_; }
  [[nodiscard]] double accel() const { return accel_; }
  [[nodiscard]] Vec2 position() const;
  [[nodiscard]] double heading() const;
  [[nodiscard]] bool lateral_busy() const { return active_lateral_.has_value() || !pending_lateral_.empty(); }
  // True once the actor has been stopped at the end of its route (reported once by the engine).
  [[nodiscard]] bool at_route_end() const { return at_end_; }
  // True once the actor brakes because its lane ends ahead (reported once by the engine).
  [[nodiscard]] bool running_out_of_road() const { return running_out_; }
  static constexpr double kEndOfLaneDecel = 3.0;  // m/s^2
  [[nodiscard]] bool walking() const { return walk_active_.has_value() || !walk_pending_.empty(); }

 private:
  void advance_longitudinal(double dt);
  void advance_lateral(double t, double dt);
  void advance_walk(double t, double dt);
  [[nodiscard]] double s_max() const;
  [[nodiscard]] double s_min() const;

  const WaypointRoute* route_;
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
  std::vector<LateralLeg> pending_lateral_;

  struct WalkLeg {
    Vec2 from, to;
    double start, duration;
  };
  std::optional<WalkLeg> walk_active_;
  std::vector<std::pair<Vec2, double>> walk_pending_;
  std::optional<Vec2> free_position_;  // set once the actor has walked off its route line
  double free_heading_ = 0;
};

}  // namespace orch::engine
