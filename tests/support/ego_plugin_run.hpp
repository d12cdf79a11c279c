#pragma once
// Runs `orchestrator run ... --ego-port P` and an ego plug-in side by side, as two child
// processes, with time limits: the way a user runs a system under test against a scenario.
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/cli_runner.hpp"

extern char** environ;

namespace orch::test {

// A child process whose stdout and stderr go to a file; killed if still running at the end.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const std::filesystem::path& output) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const int rc = posix_spawnp(&pid_, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + argv[0]);
  }
  ~Child() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  // Exit code (128 + signal if killed), or -1 if it was still running after `limit` (then
  // it is killed).
  int wait(std::chrono::duration<double> limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (true) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      if (std::chrono::steady_clock::now() >= end) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
        pid_ = -1;
        return -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  void signal(int sig) const {
    if (pid_ > 0) ::kill(pid_, sig);
  }

 private:
  pid_t pid_ = -1;
};

// A TCP port on the loopback that was free a moment ago.
inline int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    ::close(fd);
    throw std::runtime_error("no free port");
  }
  ::close(fd);
  return ntohs(a.sin_port);
}

// SUMO's own Python TraCI client (Debian's sumo-tools) running one of the test clients.
inline std::vector<std::string> python_client(const std::string& script, std::vector<std::string> args) {
  std::vector<std::string> argv{"/usr/bin/env", "PYTHONPATH=/usr/share/sumo/tools", "SUMO_HOME=/usr/share/sumo",
                                "/usr/bin/python3", source_path("tests/integration/ego_clients/" + script)};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

struct PluginRun {
  int orchestrator_exit = -1;
  int plugin_exit = -1;
  std::string orchestrator_output;
  std::string plugin_output;
  nlohmann::json result;
  double wall_s = 0;  // how long the orchestrator took
};

// Starts the orchestrator on `scenario` with an ego port, then the plug-in (every "{port}"
// in its arguments becomes the port), waits for both and reads result.json.
inline PluginRun run_with_plugin(const std::string& scenario, const TempDir& out, std::vector<std::string> plugin,
                                 std::vector<std::string> extra = {}, double plugin_limit_s = 30) {
  const std::string port = std::to_string(free_port());
  std::vector<std::string> args{ORCH_BINARY, "run", scenario, "--out", out.path().string(), "-q",
                                "--ego-port", port, "--ego-wait", "60"};
  args.insert(args.end(), extra.begin(), extra.end());
  for (auto& a : plugin) {
    const auto at = a.find("{port}");
    if (at != std::string::npos) a.replace(at, 6, port);
  }
  PluginRun r;
  const auto start = std::chrono::steady_clock::now();
  Child orchestrator(args, out / "orchestrator.out");
  Child client(plugin, out / "plugin.out");
  // The orchestrator ends first or together with a well-behaved plug-in; a plug-in that
  // hangs is killed after `plugin_limit_s`.
  r.orchestrator_exit = orchestrator.wait(std::chrono::seconds(240));
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.plugin_exit = client.wait(std::chrono::duration<double>(plugin_limit_s));
  r.orchestrator_output = slurp(out / "orchestrator.out");
  r.plugin_output = slurp(out / "plugin.out");
  if (std::filesystem::exists(out / "result.json")) r.result = read_json(out / "result.json");
  return r;
}

}  // namespace orch::test
