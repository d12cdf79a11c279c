#pragma once
// One measured actor's metrics in one step (a row of metrics.csv), the names criteria use
// for them, and the summary over a run (result.json "metrics").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "metrics/following.hpp"
#include "metrics/kinematics.hpp"
#include "sim/actor.hpp"

namespace orch::metrics {

struct ActorMetrics {
  double time = 0;
  sim::ActorId actor = 0;
  double speed = 0;  // m/s
  std::optional<Following> leader;
  std::optional<Following> follower;
  Kinematics kinematics;
  std::optional<double> lane_departure;  // m beyond the lane's markings (none: off any lane)
  std::optional<double> min_dist;        // m to the nearest other body
  std::string min_dist_to;
};

// The metric names criteria may name, in the order docs/evaluation.md lists them.
const std::vector<std::string_view>& metric_names();
// A metric's value in this step by name; none when it does not exist in this step (no
// leader, not closing, ...). `name` must be one of metric_names().
std::optional<double> metric_value(const ActorMetrics& m, std::string_view name);
// The partner a metric's value refers to ("" for the actor's own kinematics).
std::string metric_partner(const ActorMetrics& m, std::string_view name);

// An extreme over the run: the value, when, and with whom.
struct Extreme {
  double value = 0;
  double time = 0;
  std::string partner;
};

struct ActorSummary {
  sim::ActorId actor = 0;
  std::string label;  // how outputs name the actor ("" : its id): an OpenSCENARIO entity's name
  // One per row of metric_table() (metrics/metric_table.hpp), by its Summary: the extreme
  // (Min, Max, MaxAbs, OverRun) or the seconds (SecondsPositive).
  struct Row {
    std::optional<Extreme> extreme;
    double seconds = 0;
  };
  std::vector<Row> rows;

  ActorSummary();
  // Folds one step in; `dt` the step length (time weights).
  void add(const ActorMetrics& m, double dt);
  // A summary by its result.json key ("min_ttc"); throws std::invalid_argument for a key no
  // row of the table has.
  [[nodiscard]] const std::optional<Extreme>& extreme(std::string_view key) const;
  [[nodiscard]] double seconds(std::string_view key) const;
};

}  // namespace orch::metrics
