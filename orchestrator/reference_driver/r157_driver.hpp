#pragma once
// The UN R157 "competent and careful human driver" (Annex 4, Appendix 3) as an ego model.
// Pure: each step it reads what the driver sees (DriverView, built from the engine's
// WorldSnapshot by driver_view.hpp) and returns the speed the ego drives in the next step.
//
// Normal driving: the set speed, the minimum following distance of paragraph 5.2.3.3 to
// the vehicle ahead in its path, a comfortable stop behind anything standing in its path.
// A risk (a cut-in vehicle more than the wandering threshold out of its lane centre towards
// the ego's lane, a leader braking harder than the threshold, a cut-out revealing something
// in the path, a pedestrian in or entering the path, something in the path that comfortable
// braking cannot stop for) starts the Appendix 3 sequence at its risk perception point:
// risk perception time, brake reaction time (no more acceleration), then braking with the
// model's jerk up to its maximum deceleration while the situation stays critical (to a full
// stop for pedestrians and obstacles). Braking continues from the deceleration the ego
// already has; a cut-in vehicle that fully wraps the ego raises it to the second stage
// (0.85 G). One threat, one perception: a vehicle already perceived is not perceived again
// while it stays in sight and its threat is not resolved.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "reference_driver/r157_parameters.hpp"

namespace orch::reference_driver {

enum class ObjectKind { Vehicle, Pedestrian, Obstacle };

// Another road user in the ego's path frame: s along the ego's lane centre line (the ego's
// path), d to the left of it.
struct PerceivedObject {
  std::string id;
  ObjectKind kind = ObjectKind::Vehicle;
  double s = 0;        // centre, m
  double d = 0;        // centre, m (+ = left)
  double length = 0;
  double width = 0;
  double speed_s = 0;  // m/s along the path
  double speed_d = 0;  // m/s across it (+ = to the left)
  double accel_s = 0;  // m/s^2 along the path
};

struct EgoView {
  double s = 0;
  double d = 0;
  double speed = 0;
  double length = 4.5;
  double width = 1.8;
};

struct DriverView {
  double time = 0;  // s, the snapshot's
  double step = 0.05;
  EgoView ego;
  double lane_width = 3.5;        // of the ego's lane, m
  double set_speed = 0;           // m/s
  std::optional<double> path_end;  // s where the ego's path ends: its centre stops there
  std::vector<PerceivedObject> objects;
};

// The nearest object ahead in the ego's path (bodies overlapping laterally, pedestrians with
// `pedestrian_margin`) within `range`, with the bumper-to-bumper gap; null if none.
struct Ahead {
  const PerceivedObject* object = nullptr;
  double gap = 0;
};
Ahead object_ahead(const DriverView& view, double range, double pedestrian_margin);

// The ego's closest approach to what is ahead in its path over a run (minimum gap, minimum
// time to collision while closing in), from the driver's view of each step.
struct Exposure {
  std::optional<double> min_gap;  // m
  std::optional<double> min_ttc;  // s
  void add(const DriverView& view, double range);
};

enum class Phase { Drive, Perceive, React, Brake };
const char* to_string(Phase phase);

struct Decision {
  double speed = 0;  // m/s for the next step
  double accel = 0;  // m/s^2 over the next step
  Phase phase = Phase::Drive;
  std::vector<std::string> events;  // what the driver noticed or did this step, for the run log
};

class R157Driver {
 public:
  explicit R157Driver(R157Parameters parameters = {}) : p_(parameters) {}

  Decision step(const DriverView& view);

  [[nodiscard]] Phase phase() const { return phase_; }
  // The risk perception point of the risk being handled (nullopt while driving normally).
  [[nodiscard]] std::optional<double> risk_perceived_at() const {
    return phase_ == Phase::Drive ? std::nullopt : std::optional<double>(risk_at_);
  }
  [[nodiscard]] const std::string& risk() const { return risk_; }
  [[nodiscard]] const R157Parameters& parameters() const { return p_; }

 private:
  [[nodiscard]] double gap_to(const DriverView& v, const PerceivedObject& o) const;
  [[nodiscard]] bool in_path(const DriverView& v, const PerceivedObject& o) const;
  [[nodiscard]] bool entering_path(const DriverView& v, const PerceivedObject& o) const;
  [[nodiscard]] double normal_accel(const DriverView& v, const Ahead& ahead) const;
  [[nodiscard]] bool critical(const DriverView& v, const PerceivedObject& target) const;
  void update_home_lanes(const DriverView& v);
  void forget_resolved_threats(const DriverView& v);
  [[nodiscard]] bool fully_wraps(const DriverView& v, const PerceivedObject& o) const;
  [[nodiscard]] const PerceivedObject* revealed_beyond(const DriverView& v, const PerceivedObject& leader) const;
  void detect(const DriverView& v, const Ahead& ahead, Decision& out);
  void start_risk(const DriverView& v, const std::string& risk, const PerceivedObject& target, Decision& out);
  void advance_phase(const DriverView& v, Decision& out);
  [[nodiscard]] const PerceivedObject* find(const DriverView& v, const std::string& id) const;

  R157Parameters p_;
  Phase phase_ = Phase::Drive;
  double risk_at_ = 0;      // risk perception point
  std::string risk_;        // "cut-in", "decelerating lead vehicle", ...
  std::string target_;      // the object the risk concerns
  bool full_stop_ = false;  // pedestrians and obstacles: brake to a standstill
  double brake_decel_ = 0;  // m/s^2 (positive) while braking
  double last_accel_ = 0;   // of the last decision
  bool wrapped_ = false;
  std::string reused_;      // the log line of a risk that reuses an earlier perception, until it is judged    // the second braking stage (cut-in vehicle fully wrapped) began
  std::map<std::string, int> home_lane_;  // object -> lane (relative to the ego's) whose centre it last kept to
  std::string last_leader_;
  // Threat -> its risk perception point, while it stays in sight and unresolved: a later risk
  // of the same vehicle (a cut-in that becomes an obstacle in the path) is no new perception.
  std::map<std::string, double> perceived_;
  std::set<std::string> cut_out_seen_;  // leaders whose cut-out was perceived
};

}  // namespace orch::reference_driver
