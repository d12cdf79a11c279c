#pragma once
// The one metric table (docs/layout.md "Adding a metric"): each metric of a run is one entry
// holding its name, how its value is taken from a step's measurements, whom it is towards,
// its metrics.csv column(s), and its summary over the run with that summary's result.json
// key. Everything else is generated from it: the criteria's metric names and values
// (metric_names, metric_value, metric_partner), metrics.csv's header and rows (the recorder),
// the per-actor summaries (ActorSummary::add) and their result.json object (run_result.cpp),
// and the columns results/ reads back (results/run_files.cpp, through the recorder's header).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "metrics/actor_metrics.hpp"

namespace orch::metrics {

class TrajectoryBook;

// How a metric's values over a run become its result.json summary.
enum class Summary {
  None,             // no summary
  Min,              // the smallest value: {value, time[, partner]}
  Max,              // the largest value
  MaxAbs,           // the largest magnitude
  SecondsPositive,  // seconds in total (step-weighted) while the value is > 0: a number
  OverRun,          // taken at the end from the whole run's trajectories (`over_run`): {value, time, partner}
};

// What a metrics.csv column of a metric holds.
enum class Cell {
  Value,    // the step's value, 3 decimals; empty when it does not exist in that step
  Partner,  // whom the value is towards (an actor's label or a background vehicle's SUMO id), "" none
};

struct Column {
  std::string_view name{};
  Cell cell = Cell::Value;
};

struct MetricDef {
  // The name criteria use (an evaluation file's `Metric:`); "" for a metric without a value
  // per step (PET).
  std::string_view name{};
  // This step's value from the measured actor's measurements; none when it does not exist in
  // this step (no leader, not closing, ...).
  std::optional<double> (*value)(const ActorMetrics&) = nullptr;
  // Whom the value is towards; nullptr: the actor's own (kinematics, speed).
  std::string_view (*partner)(const ActorMetrics&) = nullptr;
  std::vector<Column> columns{};  // metrics.csv, in this order; none: not in the file
  Summary summary = Summary::None;
  std::string_view summary_key{};  // result.json metrics.<actor>.<key>
  // Summary::OverRun: the value for body `id` over every trajectory the run saw.
  std::optional<Extreme> (*over_run)(const TrajectoryBook&, const std::string& id) = nullptr;

  // Whether the summary names a partner ({value, time, partner}).
  [[nodiscard]] bool has_partner() const { return partner != nullptr || over_run != nullptr; }
};

// Every metric, in the order of the criteria's names and of metrics.csv's columns.
const std::vector<MetricDef>& metric_table();

// The table's rows with a summary, in result.json's order: the summaries of the runs before the
// table in their order then, the later ones in table order.
const std::vector<std::size_t>& summary_rows();

// metrics.csv's header: "time,actor_id," then every metric's columns.
std::string metrics_csv_header();

}  // namespace orch::metrics
