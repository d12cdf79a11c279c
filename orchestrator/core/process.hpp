#pragma once
// Runs an external tool (netconvert, sumo) and collects its exit code and output.
#include <filesystem>
#include <string>
#include <vector>

namespace orch {

struct ProcessResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

// Runs `program` (a path, or a name looked up in PATH) with `args`; SUMO_HOME is set for SUMO's tools when
// the caller's environment lacks it. Throws OrchError when the program cannot be started.
// `working_dir` (default: the caller's) lets tools that echo their relative input paths
// into their output (netconvert) write the same bytes wherever the files live.
ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                          const std::filesystem::path& working_dir = {});

// SUMO_HOME for SUMO's tools and XML schemas: $SUMO_HOME, else /usr/share/sumo.
std::string sumo_home();

}  // namespace orch
