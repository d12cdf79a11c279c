#include "batch/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/errors.hpp"

namespace orch::batch {

ChildProcess ChildProcess::start(const std::vector<std::string>& argv, const std::filesystem::path& log_file) {
  if (argv.empty()) throw OrchError("no program to start");
  // Everything the child needs is prepared before fork: after it, no allocation.
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int log_fd = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_fd < 0) throw OrchError("cannot open " + log_file.string() + ": " + std::strerror(errno));
  const pid_t parent = ::getpid();
  static const char kExecFailed[] = "orchestrator batch: cannot execute the run program\n";

  ChildProcess child;
  child.started_ = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const std::string why = std::strerror(errno);
    ::close(log_fd);
    throw OrchError("cannot start a run: fork failed: " + why);
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the batch died before prctl took effect
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);  // the batch blocks SIGCHLD/SIGINT/SIGTERM
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    ::execv(args[0], args.data());
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, kExecFailed, sizeof kExecFailed - 1);
    ::_exit(127);
  }
  // Also set from the parent: whichever runs first, the group exists before any kill.
  ::setpgid(pid, pid);
  ::close(log_fd);
  child.pid_ = pid;
  return child;
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(other.pid_), timed_out_(other.timed_out_), started_(other.started_) {
  other.pid_ = -1;
}

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept {
  if (this != &other) {
    kill_and_reap();
    pid_ = other.pid_;
    timed_out_ = other.timed_out_;
    started_ = other.started_;
    other.pid_ = -1;
  }
  return *this;
}

ChildProcess::~ChildProcess() { kill_and_reap(); }

void ChildProcess::kill_and_reap() {
  if (pid_ <= 0) return;
  ::kill(-pid_, SIGKILL);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

double ChildProcess::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

std::optional<ChildExit> ChildProcess::poll() {
  if (pid_ <= 0) return std::nullopt;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r != pid_) return std::nullopt;
  ChildExit exit;
  exit.wall_time_s = elapsed_s();
  exit.timed_out = timed_out_;
  if (WIFEXITED(status)) exit.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) exit.signal = WTERMSIG(status);
  // The run's own children (if any) share its group: none may outlive it.
  ::kill(-pid_, SIGKILL);
  pid_ = -1;
  return exit;
}

void ChildProcess::kill_tree(bool because_of_timeout) {
  if (pid_ <= 0) return;
  timed_out_ = timed_out_ || because_of_timeout;
  ::kill(-pid_, SIGKILL);
}

}  // namespace orch::batch
