#include "sumo_process.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <utility>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/files.hpp"

namespace orch {

namespace {

// PATH lookup in the parent: after fork only async-signal-safe calls are allowed, and
// execvp's own search may allocate.
std::string find_program(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  throw SimulationError(fmt::format("cannot start {}: not found in PATH (Debian package sumo)", name));
}

}  // namespace

void SumoProcess::spawn(const std::vector<std::string>& argv) {
  const std::string program = find_program(argv.at(0));
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw SimulationError(fmt::format("cannot start {}: fork failed", program));
  if (pid == 0) {
    // Child: only async-signal-safe calls from here to exec.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took effect
    const int null_fd = ::open("/dev/null", O_RDWR);
    if (null_fd >= 0) {
      ::dup2(null_fd, STDIN_FILENO);
      ::dup2(null_fd, STDOUT_FILENO);
      ::dup2(null_fd, STDERR_FILENO);
    }
    // No inherited sockets (an ego server's listening port) may outlive the orchestrator.
    ::syscall(SYS_close_range, 3U, ~0U, 0U);
    ::signal(SIGPIPE, SIG_DFL);
    ::execv(program.c_str(), args.data());
    ::_exit(127);
  }
  pid_ = pid;
  reaped_ = false;
}

bool SumoProcess::running() {
  if (pid_ <= 0 || reaped_) return false;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r == pid_) {
    reaped_ = true;
    status_ = status;
    return false;
  }
  return r == 0;
}

std::string SumoProcess::describe_exit() const {
  if (!reaped_) return "is running";
  if (WIFEXITED(status_)) return fmt::format("exited with status {}", WEXITSTATUS(status_));
  if (WIFSIGNALED(status_)) return fmt::format("was killed by signal {}", WTERMSIG(status_));
  return "ended";
}

bool SumoProcess::wait_exit(double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (running() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return !running();
}

void SumoProcess::stop(double grace_s) {
  if (pid_ <= 0 || reaped_) return;
  if (wait_exit(grace_s)) return;
  ::kill(pid_, SIGKILL);
  int status = 0;
  if (::waitpid(pid_, &status, 0) == pid_) {
    reaped_ = true;
    status_ = status;
  }
}

namespace {

// Whether nothing is bound to `port` on any local address (SUMO listens on all of them).
bool port_is_free(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  ::close(fd);
  return ok;
}

// The kernel's range for outgoing connections' own ports.
std::pair<int, int> ephemeral_ports() {
  std::ifstream in("/proc/sys/net/ipv4/ip_local_port_range");
  int lo = 32768;
  int hi = 60999;
  in >> lo >> hi;
  return {lo, hi};
}

}  // namespace

int free_loopback_port() {
  // Below the ephemeral range: a client polling a port from that range until SUMO listens
  // can be handed that very port as its own and connect to itself (TCP simultaneous open),
  // and then talks to its own echo.
  const auto [lo, hi] = ephemeral_ports();
  const int first = lo > 11024 ? lo - 10000 : std::max(hi + 1, 1024);
  const int span = std::min(10000, 65535 - first);
  std::mt19937 pick(static_cast<std::uint32_t>(::getpid()) ^
                    static_cast<std::uint32_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int port = first + static_cast<int>(pick() % static_cast<std::uint32_t>(span));
    if (port_is_free(port)) return port;
  }
  throw SimulationError("cannot find a free TCP port for SUMO");
}

bool port_is_listening(int port) {
  for (const char* table : {"/proc/net/tcp", "/proc/net/tcp6"}) {
    std::ifstream in(table);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      std::string slot, local, remote, state;
      fields >> slot >> local >> remote >> state;
      const auto colon = local.rfind(':');
      if (state != "0A" || colon == std::string::npos) continue;  // 0A: LISTEN
      if (std::stoi(local.substr(colon + 1), nullptr, 16) == port) return true;
    }
  }
  return false;
}

std::set<int> open_socket_fds() {
  std::set<int> fds;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    int fd = -1;
    try {
      fd = std::stoi(entry.path().filename().string());
    } catch (const std::exception&) {
      continue;
    }
    int type = 0;
    socklen_t len = sizeof type;
    if (::getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) == 0 && type == SOCK_STREAM) fds.insert(fd);
  }
  return fds;
}

int set_socket_deadline(const std::set<int>& before, int peer_port, double seconds) {
  timeval tv{};
  tv.tv_sec = static_cast<time_t>(seconds);
  tv.tv_usec = static_cast<suseconds_t>((seconds - std::floor(seconds)) * 1e6);
  int found = 0;
  for (const int fd : open_socket_fds()) {
    if (before.count(fd)) continue;
    sockaddr_storage peer{};
    socklen_t len = sizeof peer;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &len) != 0) continue;
    int port = -1;
    if (peer.ss_family == AF_INET) port = ntohs(reinterpret_cast<const sockaddr_in*>(&peer)->sin_port);
    if (peer.ss_family == AF_INET6) port = ntohs(reinterpret_cast<const sockaddr_in6*>(&peer)->sin6_port);
    if (port != peer_port) continue;
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    ++found;
  }
  return found;
}

std::string sumo_errors_in(const std::string& text) {
  std::string out;
  std::istringstream in(text);
  bool in_error = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("Error: ", 0) == 0) {
      out += (out.empty() ? "" : " ") + line.substr(7);
      in_error = true;
    } else if (in_error && !line.empty() && line.front() == ' ') {
      out += " " + line.substr(line.find_first_not_of(' '));
    } else {
      in_error = false;
    }
  }
  return out;
}

std::string sumo_errors_in_file(const std::string& path) {
  try {
    return sumo_errors_in(read_file(path));
  } catch (const OrchError&) {
    return "";  // no log (yet): nothing SUMO said
  }
}

}  // namespace orch
