#pragma once
// The operating-system side of the traci backend, no SUMO headers: the sumo / sumo-gui
// child process, a free loopback port for it, read deadlines on the TraCI socket, and
// SUMO's own error messages from its log.
//
// Why not libtraci::Simulation::start: it runs `sumo ... &` through a shell (popen), so the
// child's pid is unknown, it survives an orchestrator that is killed, and arguments with
// spaces break. Here the child is forked directly, dies with its parent (PR_SET_PDEATHSIG),
// lives in its own process group (a Ctrl-C in the terminal reaches only the orchestrator,
// which ends the run cleanly), and is always reaped.
#include <sys/types.h>

#include <set>
#include <string>
#include <vector>

namespace orch {

class SumoProcess {
 public:
  SumoProcess() = default;
  ~SumoProcess() { stop(0.0); }
  SumoProcess(const SumoProcess&) = delete;
  SumoProcess& operator=(const SumoProcess&) = delete;

  // Starts argv[0] (looked up in PATH) with stdin/stdout/stderr on /dev/null (SUMO writes
  // everything to its --log file). Throws SimulationError when it cannot be started.
  void spawn(const std::vector<std::string>& argv);
  // False once the child has exited (it is reaped then).
  bool running();
  // Waits up to `seconds` for the child to exit by itself; true if it did.
  bool wait_exit(double seconds);
  // "exited with status 1", "was killed by signal 9", or "is running".
  [[nodiscard]] std::string describe_exit() const;
  [[nodiscard]] bool started() const { return pid_ > 0; }
  // Waits up to `grace_s` for the child to exit by itself, then kills it (SIGKILL) and
  // reaps it. Nothing is left behind whatever state it was in.
  void stop(double grace_s);

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = 0;
};

// A TCP port nobody uses right now, outside the kernel's ephemeral range. Throws
// SimulationError.
int free_loopback_port();
// Whether some process listens on `port` (Linux /proc/net/tcp, tcp6): the time to connect,
// without knocking on a port that is not open yet.
bool port_is_listening(int port);

// The file descriptors of this process that are sockets.
std::set<int> open_socket_fds();
// Every TCP socket opened since `before` whose peer port is `peer_port` gets a receive and
// send deadline: a blocking read on it fails after `seconds` instead of waiting forever.
// Returns how many sockets it found (libtraci keeps its socket private; this finds it).
int set_socket_deadline(const std::set<int>& before, int peer_port, double seconds);

// SUMO's error messages ("Error: ..." and their indented continuation lines) in a log file,
// joined into one line; empty when there are none.
std::string sumo_errors_in(const std::string& text);
std::string sumo_errors_in_file(const std::string& path);

}  // namespace orch
