#pragma once
// `orchestrator batch`: every planned run as one child `orchestrator run` (libsumo allows
// one simulation per process), `jobs` at a time, with timeouts and retries of errors.
//
// Folder of a batch (--out):
//   batch.json                       the plan (manifest.hpp), written first
//   runs/{L}_{P}/                    scenario.json (bound template), result.json, trace.csv,
//                                    run.log, sumo.log, child.log (the child's terminal)
//   executions/execution_{L}_{P}.json  the execution trace, written atomically and last
//   summary.json, junit.xml, summary.txt  at the end, from the execution traces
//
// A run is done exactly when its execution trace exists. Killed at any moment (even the
// batch by SIGKILL: its children die with it), `--resume DIR` wipes the folders of runs
// without a trace and runs exactly those again.
#include <filesystem>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "batch/batch_plan.hpp"
#include "batch/run_queue.hpp"
#include "core/fork_checkpoint.hpp"

namespace orch::batch {

struct BatchOptions {
  std::vector<std::string> inputs;  // logical scenarios and/or parameter files
  std::filesystem::path out;
  bool resume = false;  // inputs, shard and defaults come from out/batch.json
  std::optional<int> jobs;            // default: the number of cores
  std::optional<double> timeout_s;    // per attempt; default 1800 s
  std::optional<int> retries;         // extra attempts for errors; default 1
  std::optional<Shard> shard;
  std::vector<std::string> map_dirs;  // passed to each run as --maps
  std::string catalog;                // passed to each run as --catalog
  bool ssm = false;                   // passed to each run as --ssm (SUMO's SSM device on the ego)
  // --fork: the sets of a logical scenario run with one seed and share their common prefix
  // (docs/forking.md); sets that share a seed and settings share it anyway (--no-fork: never).
  bool fork = false;
  bool no_fork = false;
  std::optional<ForkCheckpoint> fork_at;  // --fork-at: passed to every group's process
  std::string wrapper;                // program each run is started through (nice, a test double)
  std::filesystem::path orchestrator; // the binary to run children with
  // Flags `orchestrator run` offers; a sumo_config value (traffic, backend) is passed only
  // through a flag the binary has, and is an error otherwise.
  std::set<std::string> run_flags;
  // Flags every run gets as they are (batch --ego-model, --reference-run).
  std::vector<std::string> run_args;
  std::ostream* out_stream = nullptr;
  bool terminal = false;
};

// Returns the exit status: 0 all success, 1 some failure, 2 any error, 3 interrupted
// (SIGINT/SIGTERM: runs left to --resume). Throws ScenarioError / OrchError for bad inputs
// before any run starts.
int run_batch(const BatchOptions& options);

// Runs `tasks` (indices into plan.runs) into `out` exactly as a batch does: run folders,
// retries, the execution trace written last. `options` has jobs, timeout_s and retries set;
// `already_done` runs count as finished in the progress display. The batch runs its whole
// plan through it once; the search (batch/search_runner.hpp) one iteration at a time.
QueueOutcome execute_planned_runs(const BatchOptions& options, const BatchPlan& plan,
                                  const std::vector<std::size_t>& tasks, const std::filesystem::path& out,
                                  std::size_t already_done);

// Adds run flags for the pass-through settings of a sumo_config: {"--traffic", value}, ...
// Throws OrchError naming the setting when `run_flags` lacks its flag.
std::vector<std::string> pass_through_flags(const SumoConfig& config, const std::set<std::string>& run_flags);

// The child's command line for one run (without a wrapper): `orchestrator run
// scenario_file` (the bound template in the run folder, template_file.hpp, or the scenario
// of an OpenSCENARIO variation) into `run_dir`.
std::vector<std::string> run_command_line(const BatchOptions& options, const PlannedRun& run,
                                          const std::filesystem::path& run_dir,
                                          const std::filesystem::path& scenario_file);

}  // namespace orch::batch
