#pragma once
// Points this process's stderr elsewhere for a while. libsumo runs SUMO inside this process:
//   - while SUMO starts, stderr goes to an anonymous file (Capture): some errors (a broken
//     net) are printed only there, and libsumo throws a bare "Process Error";
//   - while SUMO runs, stderr goes to /dev/null (Silence): SUMO prints every warning to
//     stderr as well as to its --log file, and the run's own terminal output must stay
//     readable; everything SUMO says is in sumo.log. ORCH_SUMO_STDERR=1 keeps stderr as it
//     is then (for debugging crashes inside SUMO).
#include <string>

namespace orch {

class StderrRedirect {
 public:
  enum class Target { Silence, Capture };
  StderrRedirect() = default;  // stderr untouched until engage
  explicit StderrRedirect(Target target) { engage(target); }
  ~StderrRedirect() { release(); }
  StderrRedirect(const StderrRedirect&) = delete;
  StderrRedirect& operator=(const StderrRedirect&) = delete;

  void engage(Target target);
  // Restores stderr; returns what was written meanwhile when capturing.
  std::string release();

 private:
  int saved_ = -1;  // the real stderr while redirected
  int file_ = -1;   // the capture file
};

}  // namespace orch
