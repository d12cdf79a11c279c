#pragma once
// The execution trace (ATLAS `execution_{logical_uuid}_{parameter_uuid}.json`, seed 003):
// the record of one run, linking it back to its parameter set, logical scenario, abstract
// scenario and requirement. In place of the seed's `python_file` the implementation names
// the bound scenario file and its template. Written atomically, and last: a run counts as
// done exactly when its execution trace exists.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "batch/attempt.hpp"
#include "batch/batch_plan.hpp"

namespace orch::batch {

struct ExecutionRecord {
  std::string execution_uuid;
  std::string executed_at;  // start of the final attempt
  std::vector<std::string> command;
  std::vector<Attempt> attempts;  // oldest first; the last decides
  // The run's fork.json when it shared its prefix with other runs (docs/forking.md): from
  // where it was forked and the simulated seconds it saved; null otherwise.
  nlohmann::ordered_json fork;
};

// The trace's text. Input files are named by absolute path; outputs relative to the batch
// folder, so that a batch folder (or a shard's) can be moved or merged as a whole.
std::string execution_trace_text(const PlannedRun& run, const PlannedLogical& logical, const ExecutionRecord& record);

// executions/execution_{L}_{P}.json inside the batch folder.
std::filesystem::path execution_trace_path(const std::filesystem::path& batch_dir, const std::string& run_id);

// What summaries need from a trace.
struct ExecutionSummary {
  std::string run_id;
  std::string logical_uuid;
  std::string parameter_uuid;
  std::string name;
  std::optional<long long> seed;
  nlohmann::json sampled_values;
  std::string verdict;
  std::string reason;
  int attempts = 0;
  std::optional<double> sim_time;
  double wall_time_s = 0;  // all attempts
  std::string run_dir;     // relative to the batch folder
  nlohmann::json metrics;   // the run's metrics summary (result.json "metrics"; null: none)
  nlohmann::json criteria;  // the run's criteria (result.json "criteria"; null: none)
  std::string preventable;  // result.json "preventable" (--reference-run); "" if none
  std::filesystem::path file;
};

// Reads a trace written by execution_trace_text. Throws ScenarioError (file, line, pointer)
// when it is not one.
ExecutionSummary read_execution_summary(const std::filesystem::path& file);

// `run --flag` words of argv joined as a shell would need them quoted.
std::string shell_command(const std::vector<std::string>& argv);

}  // namespace orch::batch
