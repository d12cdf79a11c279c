#pragma once
// One function per subcommand, each returning the exit code; their options are registered in
// cli/subcommands.cpp (cli/subcommand.hpp).
#include <filesystem>
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
  std::vector<std::string> parameters;  // --param NAME=VALUE (OpenSCENARIO files)
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
  // External ego plug-in (docs/ego-plugin.md): with a port, a TraCI client drives
  // the ego in lockstep.
  std::optional<int> ego_port;           // --ego-port (0: any free port)
  std::string ego_entity;                // --ego NAME: the ego of an OpenSCENARIO run
  std::vector<std::string> parameters;   // --param NAME=VALUE (OpenSCENARIO runs)
  std::string ego_model;                 // --ego-model sumo|r157|cruise ("" = sumo, or the evaluation file's)
  bool reference_run = false;            // --reference-run: again with the R157 reference driver
  std::string controllers = "on";        // --controllers on|off: off, every entity follows the storyboard
  std::string ego_address = "127.0.0.1";  // --ego-address: loopback unless asked otherwise
  double ego_wait = 60;                  // --ego-wait, s to wait for the plug-in to connect
  double ego_timeout = 30;               // --ego-timeout, s to wait for its next message
  // Background traffic and backends (docs/background-traffic.md, "Backends").
  std::string traffic;            // --traffic LEVEL|VEH_PER_H_PER_LANE|FILE; empty: the scenario's own
  bool trace_background = false;  // --trace-background
  bool no_report = false;         // --no-report: no report.html (README "Looking at results")
  bool video = false;             // --video: video.mp4 of the run (sumo-gui, ffmpeg)
  std::string backend;            // --backend libsumo|traci; empty: libsumo, traci with --gui/--connect
  bool gui = false;               // --gui: sumo-gui (traci backend)
  std::string connect;            // --connect HOST:PORT: a running SUMO (traci backend)
  std::optional<double> realtime; // --realtime FACTOR
  double sumo_timeout = 10;       // --sumo-timeout, s (traci backend; 0: wait forever)
  // Evaluation files (docs/evaluation.md): a result.jsonl frame line every N steps, and the
  // run options given on the command line, which override the file's Conditions.
  int jsonl_every = 1;
  std::vector<std::string> given;  // e.g. "--step", "--seed"
  bool ssm = false;  // --ssm: SUMO's SSM device on a SUMO-driven ego (ssm.xml)
  // --fork-with FILE --fork-out DIR (repeatable, in pairs): more variants of the scenario,
  // run with the same options, sharing SUMO while they give the same commands (docs/forking.md).
  std::vector<std::string> fork_with;
  std::vector<std::string> fork_out;
  std::optional<std::string> fork_at;  // --fork-at SECONDS|EVENT: a requested checkpoint (core/fork_checkpoint.hpp)
  // --fork-param K:NAME=VALUE: the K-th --fork-with variant's own --param (OpenSCENARIO)
  std::vector<std::string> fork_params;
};
int run_command(const RunOptions& o);
}  // namespace orch::cli
namespace orch {
struct RunRequest;
struct SumoBackendOptions;
}  // namespace orch
namespace orch::cli {
// `run FILE --fork-with FILE2 --fork-out DIR2 ...`: the variants with one request's options
// (cli/fork_run.cpp).
int run_forked(const RunOptions& o, const RunRequest& request, const std::string& backend,
               const SumoBackendOptions& sumo_options);

// `orchestrator report DIR...`: (re)writes report.html of run folders and batch folders.
struct ReportOptions {
  std::vector<std::string> dirs;
};
int report_command(const ReportOptions& o);
// Writes the report of a run folder / batch folder and prints "report: file://..."; a report
// that cannot be written is a warning on stderr, never a changed verdict. Returns false then.
bool announce_run_report(const std::filesystem::path& run_dir);
// video.mp4 of a run folder, "video: file://..."; a failure is a warning on stderr.
bool announce_video(const std::filesystem::path& run_dir);
// video.mp4 of every run of a batch folder whose verdict is failure.
void announce_failure_videos(const std::filesystem::path& batch_dir);
bool announce_batch_report(const std::vector<std::filesystem::path>& batch_dirs, const std::filesystem::path& out_dir);

// `orchestrator baseline`: a map's background traffic in SUMO alone, no scenario; what
// the benchmark measures the orchestrator against (docs/performance.md).
struct BaselineOptions {
  CommonOptions common;
  std::string map;
  std::string traffic = "dense";
  int steps = 1000;
  double step = 0.05;
  long long seed = 42;
  std::string backend = "libsumo";
  std::string out = "out/baseline";
};
int baseline_command(const BaselineOptions& o);

// `orchestrator map traffic`: writes the maps' background traffic files.
struct MapTrafficOptions {
  CommonOptions common;
  std::vector<std::string> maps;  // empty: every map found
  std::optional<double> rate;     // --rate: one file at this many vehicles/hour/lane (needs --out)
  double fill_per_km = -1;        // --fill-per-km: vehicles per km and lane at the start (with --rate)
  std::string out;                // --out FILE for --rate
};
int map_traffic_command(const MapTrafficOptions& o);

}  // namespace orch::cli
