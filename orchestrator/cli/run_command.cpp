// TEMPORARY placeholder while the command is being written (this session).
#include <iostream>

#include "cli/commands.hpp"

namespace orch::cli {
int run_command(const RunOptions&) {
  std::cerr << "run_command: not written yet\n";
  return 2;
}
}  // namespace orch::cli
