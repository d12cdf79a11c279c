// TEMPORARY placeholder while the command is being written (this session).
#include <iostream>

#include "cli/commands.hpp"

namespace orch::cli {
int map_build_command(const MapBuildOptions&) {
  std::cerr << "map_build_command: not written yet\n";
  return 2;
}
int map_check_command(const MapCheckOptions&) {
  std::cerr << "map_check_command: not written yet\n";
  return 2;
}
}  // namespace orch::cli
