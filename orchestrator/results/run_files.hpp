#pragma once
// One run folder read back (README "Outputs"): result.json, trace.csv, metrics.csv,
// background.csv, traffic_actions.csv and run.log. What a run did not write (a run that failed before SUMO
// started has no trace; metrics exist only when the evaluation wrote them) is absent, not
// an error; a file that is there but of the wrong shape is an error naming it.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "results/csv_table.hpp"

namespace orch {

struct RunFiles {
  std::filesystem::path dir;
  nlohmann::json result;  // result.json
  std::optional<CsvTable> trace;
  std::optional<CsvTable> metrics;
  std::optional<CsvTable> background;
  std::optional<CsvTable> traffic_actions;  // an OpenSCENARIO run's TrafficAction vehicles
  std::string run_log;  // "" when there is none
};

// Reads result.json (required: throws ScenarioError with line and pointer when it is not
// JSON, OrchError when missing) and whatever else of the run is in `dir`. A malformed
// optional file throws OrchError too, unless `problems` is given: then the file is left out
// and the message added there (a report still shows what can be shown).
RunFiles read_run_files(const std::filesystem::path& dir, std::vector<std::string>* problems = nullptr);

// The trace's columns every reader relies on (a subset of the writer's header).
const std::vector<std::string>& trace_columns();
// metrics.csv's: every column the writer's header has (metrics/metric_table.hpp generates it).
const std::vector<std::string>& metrics_columns();
const std::vector<std::string>& background_columns();
const std::vector<std::string>& traffic_actions_columns();

}  // namespace orch
