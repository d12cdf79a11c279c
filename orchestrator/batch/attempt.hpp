#pragma once
// The verdict of one attempt of one run, from how its child process ended and the
// result.json it wrote. The child's contract (docs/outputs.md): exit 0 success, 1 failure,
// 2 error, result.json always written once the run started. Anything else -- a signal, a
// timeout, a missing or unreadable result, an exit code that contradicts the result -- is an
// `error` of the batch (could not run), never a test `failure`.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "batch/child_process.hpp"

namespace orch::batch {

struct Attempt {
  int number = 1;
  std::string started_at;
  std::string verdict = "error";  // success | failure | error
  std::string reason;
  std::optional<int> exit_code;
  std::optional<int> signal;
  bool timed_out = false;
  double wall_time_s = 0;          // as the batch measured it: start-up to exit
  std::optional<double> sim_time;  // from result.json
  std::optional<double> run_wall_time_s;  // result.json's wall_time_s: inside the run
  nlohmann::json metrics;   // result.json's metrics summary (null: none)
  nlohmann::json criteria;  // result.json's criteria (null: none)
  std::string preventable;  // result.json's "preventable" (--reference-run), "" if none
};

Attempt judge_attempt(const ChildExit& exit, const std::string& start_error, const std::filesystem::path& result_file,
                      std::optional<double> timeout_s);

// An error is worth another attempt (a crash, a timeout, SUMO failing); a failure is the
// scenario's judgement and is never retried.
inline bool should_retry(const Attempt& a, int max_attempts) { return a.verdict == "error" && a.number < max_attempts; }

// The exit status a run's result.json verdict stands for (0 success, 1 failure, 2 error);
// nullopt when it has none that reads. For the runs of a forked group, whose one process
// exits with the worst of them.
std::optional<int> verdict_exit_code(const std::filesystem::path& result_file);

}  // namespace orch::batch
