#pragma once
// One function per subcommand; main.cpp only parses arguments. Each returns the exit code.
#include <optional>
#include <string>
#include <vector>

namespace orch::cli {

// Options every command that needs maps or models shares.
struct CommonOptions {
  std::vector<std::string> map_dirs;  // --maps DIR (repeatable); default: $ORCH_MAPS, sumo_nets/
  std::string catalog;                // --catalog FILE; default: the compiled-in catalog
};

struct ValidateOptions {
  CommonOptions common;
  std::vector<std::string> files;
  bool strict = false;  // warnings count as errors
  bool quiet = false;   // only errors and the summary
};
int validate_command(const ValidateOptions& o);

struct MapBuildOptions {
  CommonOptions common;
  std::vector<std::string> maps;  // map ids or folders to rebuild (empty with --waypoints: new map)
  std::string waypoints;          // --waypoints FILE: build a new map from this file
  std::string id;                 // --id for a new map
  std::vector<std::string> aliases;
  std::string out;                // --out DIR for a new map
};
int map_build_command(const MapBuildOptions& o);

struct MapCheckOptions {
  CommonOptions common;
  std::vector<std::string> maps;  // empty = every map found
  double tolerance = 0.10;        // m; exit status 1 when any waypoint is farther from its lane centre
};
int map_check_command(const MapCheckOptions& o);

struct RunOptions {
  CommonOptions common;
  std::string file;
  std::string out = "out";
  double step = 0.05;
  long long seed = 42;
  std::optional<double> max_time;
  bool strict = false;
  bool quiet = false;
};
int run_command(const RunOptions& o);

}  // namespace orch::cli
