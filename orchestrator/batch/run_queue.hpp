#pragma once
// Runs tasks as child processes, `jobs` at a time, each with a wall-clock timeout after
// which its whole process tree is killed. A task whose attempt ends badly may be tried
// again (the caller decides); a crashing or hanging child never stops the queue.
//
// The queue waits for SIGCHLD with sigtimedwait instead of polling: a finished child is
// noticed at once. SIGINT and SIGTERM are waited for the same way: the queue then kills
// every running child and returns, leaving those tasks unfinished for a resume.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "batch/child_process.hpp"

namespace orch::batch {

struct Launch {
  std::vector<std::string> argv;  // argv[0]: absolute path of the program
  std::filesystem::path log_file;
};

struct QueueCallbacks {
  // Prepares attempt `attempt` (1, 2, ...) of task `task`: writes its inputs, returns the
  // command. An exception here counts as a failed start of that attempt.
  std::function<Launch(std::size_t task, int attempt)> prepare;
  // Called once per ended attempt (also a failed start: exit_code 127, no process). Returns
  // true to try the task again, false when the task is finished.
  std::function<bool(std::size_t task, int attempt, const ChildExit& exit, const std::string& start_error)> ended;
  // Called about every `tick_s` while the queue waits (progress display); may be empty.
  std::function<void()> tick;
};

struct QueueOptions {
  int jobs = 1;
  std::optional<double> timeout_s;  // per attempt, wall clock
  double tick_s = 0.5;
};

struct QueueOutcome {
  bool interrupted = false;      // SIGINT/SIGTERM: running tasks were killed, not reported
  std::vector<std::size_t> unfinished;  // tasks not finished (only when interrupted)
};

QueueOutcome run_queue(const std::vector<std::size_t>& tasks, const QueueOptions& options,
                       const QueueCallbacks& callbacks);

}  // namespace orch::batch
