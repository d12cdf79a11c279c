#pragma once
// Starting the orchestrator binary in the background and looking at its child processes,
// for tests of what happens when SUMO dies or hangs under it (Linux /proc).
#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace orch::test {

struct ProcInfo {
  pid_t ppid = 0;
  char state = '?';
  std::string comm;
};

inline std::optional<ProcInfo> proc_info(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!in || !std::getline(in, text)) return std::nullopt;
  const auto open = text.find('(');
  const auto close = text.rfind(')');
  if (open == std::string::npos || close == std::string::npos) return std::nullopt;
  ProcInfo p;
  p.comm = text.substr(open + 1, close - open - 1);
  std::istringstream rest(text.substr(close + 2));
  rest >> p.state >> p.ppid;
  return p;
}

// Running and not a zombie (a killed process whose parent is gone may stay a zombie until
// the container's init reaps it; it holds no resources and runs nothing).
inline bool process_alive(pid_t pid) {
  const auto p = proc_info(pid);
  return p && p->state != 'Z' && p->state != 'X';
}

// The first child of `parent` whose command name is `comm`, waiting up to `seconds`.
inline std::optional<pid_t> find_child(pid_t parent, const std::string& comm, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
      const std::string name = entry.path().filename().string();
      if (name.find_first_not_of("0123456789") != std::string::npos) continue;
      const pid_t pid = std::stoi(name);
      const auto p = proc_info(pid);
      if (p && p->ppid == parent && p->comm == comm && p->state != 'Z') return pid;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::nullopt;
}

// The orchestrator binary with `args`, output to `log`, in the background.
inline pid_t spawn_cli(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<std::string> argv{ORCH_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> c_args;
  for (auto& a : argv) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
    }
    ::execv(c_args[0], c_args.data());
    ::_exit(127);
  }
  return pid;
}

// Exit status of `pid` (128 + signal if killed), or nullopt if it is still running after
// `seconds` (then it is killed).
inline std::optional<int> wait_for_exit(pid_t pid, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  return std::nullopt;
}

}  // namespace orch::test
