#pragma once
// Runs an external tool (netconvert, sumo) and collects its exit code and output.
#include <string>
#include <vector>

namespace orch {

struct ProcessResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

// Runs `program` (looked up in PATH) with `args`; SUMO_HOME is set for SUMO's tools when
// the caller's environment lacks it. Throws OrchError when the program cannot be started.
ProcessResult run_process(const std::string& program, const std::vector<std::string>& args);

// SUMO_HOME for SUMO's tools and XML schemas: $SUMO_HOME, else /usr/share/sumo.
std::string sumo_home();

}  // namespace orch
