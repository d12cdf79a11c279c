#pragma once
// libsumo runs SUMO inside this process, and SUMO prints every warning to stderr as well as
// to its --log file. The run's own terminal output must stay readable, so while SUMO runs
// in-process stderr points to /dev/null; everything SUMO says is in sumo.log.
// ORCH_SUMO_STDERR=1 keeps stderr as it is (for debugging crashes inside SUMO).
#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace orch {

class ConsoleSilencer {
 public:
  ConsoleSilencer() = default;
  ConsoleSilencer(const ConsoleSilencer&) = delete;
  ConsoleSilencer& operator=(const ConsoleSilencer&) = delete;
  ~ConsoleSilencer() { release(); }

  void engage() {
    if (saved_ >= 0) return;
    const char* keep = std::getenv("ORCH_SUMO_STDERR");
    if (keep && std::strcmp(keep, "1") == 0) return;
    const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null_fd < 0) return;
    saved_ = ::dup(STDERR_FILENO);
    ::dup2(null_fd, STDERR_FILENO);
    ::close(null_fd);
  }

  void release() {
    if (saved_ < 0) return;
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
  }

 private:
  int saved_ = -1;
};

}  // namespace orch
