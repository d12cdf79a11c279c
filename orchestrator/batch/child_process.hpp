#pragma once
// One child process of a batch: its own process group (so that a timeout kills the whole
// tree it may have started), its output in a log file, and killed by the kernel when the
// batch process dies, even by SIGKILL (Linux PR_SET_PDEATHSIG), so that a resumed batch
// never races an orphan of the killed one writing the same run folder.
//
// fork + exec rather than posix_spawn or Boost.Process: posix_spawn has no hook for
// PR_SET_PDEATHSIG, and Boost.Process 1.74's timed waits are unreliable. Between fork and
// exec the child calls only async-signal-safe functions.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace orch::batch {

struct ChildExit {
  std::optional<int> exit_code;  // set when the child exited normally
  std::optional<int> signal;     // set when a signal ended it (also after a timeout kill)
  bool timed_out = false;
  double wall_time_s = 0;
};

class ChildProcess {
 public:
  // Starts argv[0] (an absolute path) with stdout and stderr appended to `log_file`.
  // Throws OrchError when it cannot fork or open the log. A program that cannot be
  // executed exits with status 127 and a line in the log.
  static ChildProcess start(const std::vector<std::string>& argv, const std::filesystem::path& log_file);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();  // kills and reaps a child that is still running

  [[nodiscard]] pid_t pid() const { return pid_; }
  [[nodiscard]] double elapsed_s() const;
  // Non-blocking: the exit once the child has ended (and is reaped), else nullopt.
  std::optional<ChildExit> poll();
  // SIGKILL to the child's whole process group; poll() then reports it as timed out.
  void kill_tree(bool because_of_timeout);

 private:
  ChildProcess() = default;
  void kill_and_reap();
  pid_t pid_ = -1;
  bool timed_out_ = false;
  std::chrono::steady_clock::time_point started_;
};

}  // namespace orch::batch
