// orchestrator: runs ScenarioExecutor scenarios on SUMO. See README.md.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/commands.hpp"
#include "core/utf8.hpp"

namespace {

void add_common(CLI::App* app, orch::cli::CommonOptions& c) {
  // One value per --maps, so that `--maps DIR a.json b.json` keeps both files as files.
  app->add_option("--maps", c.map_dirs, "Folder holding map folders (repeatable; default: $ORCH_MAPS, then sumo_nets/)")
      ->allow_extra_args(false);
  app->add_option("--catalog", c.catalog, "Model catalog JSON replacing the built-in one");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"orchestrator: runs ScenarioExecutor scenarios on SUMO"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("orchestrator ") + ORCH_VERSION);

  orch::cli::ValidateOptions validate;
  auto* v = app.add_subcommand("validate", "Check scenario files without running them");
  // No ExistingFile checks on scenario files: a missing or unreadable file is reported like
  // any bad input (validate: INVALID, exit 1; run: result.json with verdict error, exit 2).
  v->add_option("files", validate.files, "Scenario files")->required();
  v->add_flag("--strict", validate.strict, "Treat warnings as errors");
  v->add_flag("-q,--quiet", validate.quiet, "Print only errors and the summary");
  v->add_option("--param", validate.parameters, "NAME=VALUE: set an OpenSCENARIO parameter (repeatable)")
      ->allow_extra_args(false);
  add_common(v, validate.common);

  orch::cli::RunOptions run;
  auto* r = app.add_subcommand("run", "Run one scenario on SUMO");
  r->add_option("file", run.file, "Scenario file")->required();
  r->add_option("--out", run.out, "Output folder (result.json, trace.csv, run.log)")->capture_default_str();
  r->add_option("--step", run.step, "Simulation step, s")->capture_default_str()->check(CLI::Range(0.001, 1.0));
  r->add_option("--seed", run.seed, "Random seed for SUMO")->capture_default_str();
  r->add_option("--max-time", run.max_time, "End the run (verdict failure) at this simulation time, s")
      ->check(CLI::PositiveNumber);
  r->add_flag("--strict", run.strict, "Refuse to run a scenario with validation warnings");
  r->add_flag("-q,--quiet", run.quiet, "Do not echo the run log to the terminal");
  r->add_option("--ego-port", run.ego_port,
                "An external plug-in drives the ego over TraCI: listen on this port (0: any free port)")
      ->check(CLI::Range(0, 65535));
  r->add_option("--ego", run.ego_entity, "OpenSCENARIO runs: the entity that is the ego (default: the ALKSController's)");
  r->add_option("--ego-model", run.ego_model,
                "What drives the ego when no plug-in does: sumo (SUMO's car-following model, default) or r157 (the UN "
                "R157 reference driver, docs/reference-driver.md)")
      ->check(CLI::IsMember({"sumo", "r157"}));
  r->add_flag("--reference-run", run.reference_run,
              "Run the scenario again with the R157 reference driver (into reference/) and judge whether a collision "
              "was preventable");
  r->add_option("--ego-address", run.ego_address, "Address the ego TraCI server listens on")->capture_default_str();
  r->add_option("--ego-wait", run.ego_wait, "Seconds to wait for the ego plug-in to connect")
      ->capture_default_str()->check(CLI::PositiveNumber);
  r->add_option("--ego-timeout", run.ego_timeout, "Seconds the world waits for the ego plug-in's next message")
      ->capture_default_str()->check(CLI::PositiveNumber);
  r->add_option("--traffic", run.traffic,
                "Background traffic: none, light, medium, dense, vehicles per hour and lane, or a SUMO route file "
                "(default: the scenario's own \"traffic\", else none)");
  r->add_flag("--trace-background", run.trace_background, "Write background.csv: background vehicles near the actors");
  r->add_flag("--no-report", run.no_report, "Do not write report.html");
  r->add_flag("--video", run.video, "Write video.mp4: the run replayed in sumo-gui (under Xvfb without a display)");
  r->add_option("--backend", run.backend, "SUMO client library: libsumo (in-process, default) or traci")
      ->check(CLI::IsMember({"libsumo", "traci"}));
  r->add_flag("--gui", run.gui, "Watch the run in sumo-gui (traci backend)");
  r->add_option("--connect", run.connect, "Use a SUMO already running with --remote-port, at HOST:PORT (traci backend)");
  r->add_option("--realtime", run.realtime, "Advance at most FACTOR times as fast as wall-clock time (1 = real time)")
      ->check(CLI::PositiveNumber);
  r->add_option("--sumo-timeout", run.sumo_timeout,
                "Seconds without an answer from SUMO before the run ends as an error (traci backend; 0: no limit)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  r->add_option("--jsonl-every", run.jsonl_every, "Evaluation files: a result.jsonl frame line every N steps")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  add_common(r, run.common);

  orch::cli::BaselineOptions baseline;
  auto* bl = app.add_subcommand("baseline", "Run a map's background traffic in SUMO alone, without a scenario");
  bl->add_option("map", baseline.map, "Map id or folder")->required();
  bl->add_option("--traffic", baseline.traffic, "Background traffic, as for run")->capture_default_str();
  bl->add_option("--steps", baseline.steps, "Simulation steps")->capture_default_str()->check(CLI::PositiveNumber);
  bl->add_option("--step", baseline.step, "Simulation step, s")->capture_default_str()->check(CLI::Range(0.001, 1.0));
  bl->add_option("--seed", baseline.seed, "Random seed for SUMO")->capture_default_str();
  bl->add_option("--backend", baseline.backend, "libsumo or traci")->capture_default_str()
      ->check(CLI::IsMember({"libsumo", "traci"}));
  bl->add_option("--out", baseline.out, "Folder for sumo.log")->capture_default_str();
  add_common(bl, baseline.common);

  auto* map = app.add_subcommand("map", "Build and check SUMO networks for RoadEditor maps");
  map->require_subcommand(1);
  orch::cli::MapBuildOptions build;
  auto* mb = map->add_subcommand("build", "Generate the SUMO net of a map from its waypoint file");
  mb->add_option("maps", build.maps, "Map ids or folders to rebuild (default with no --waypoints: all)");
  mb->add_option("--waypoints", build.waypoints, "Build a new map from this RoadEditor waypoint file")
      ->check(CLI::ExistingFile);
  mb->add_option("--id", build.id, "Id of the new map (default: the waypoint file's mapId)");
  mb->add_option("--alias", build.aliases, "Extra name scenarios may use for the new map (repeatable)");
  mb->add_option("--out", build.out, "Folder of the new map (default: sumo_nets/<id>)");
  add_common(mb, build.common);
  orch::cli::MapCheckOptions check;
  auto* mc = map->add_subcommand("check", "Print, per route, the largest waypoint-to-lane-centre distance");
  mc->add_option("maps", check.maps, "Map ids or folders (default: all)");
  mc->add_option("--tolerance", check.tolerance, "Largest acceptable distance, m")->capture_default_str();
  add_common(mc, check.common);
  orch::cli::MapTrafficOptions traffic;
  auto* mt = map->add_subcommand("traffic", "Generate the background traffic files of maps (traffic/<level>.rou.xml)");
  mt->add_option("maps", traffic.maps, "Map ids or folders (default: all)");
  mt->add_option("--rate", traffic.rate, "Write one file at this many vehicles per hour and lane (with --out)")
      ->check(CLI::NonNegativeNumber);
  mt->add_option("--fill-per-km", traffic.fill_per_km,
                 "With --rate: vehicles per km and lane placed at the start (default: the rate's steady state)");
  mt->add_option("--out", traffic.out, "File for --rate");
  add_common(mt, traffic.common);

  orch::cli::ReportOptions report;
  auto* rp = app.add_subcommand("report", "Write report.html of run folders and batch folders again");
  rp->add_option("dirs", report.dirs, "Run folders (with result.json) or batch folders (with batch.json)")
      ->required()->check(CLI::ExistingDirectory);

  const auto batch_commands = orch::cli::add_batch_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every usage error is an error (2), like the rest.
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    if (*v) return orch::cli::validate_command(validate);
    if (*r) {
      for (const char* name : {"--step", "--seed", "--max-time", "--traffic", "--backend", "--ego-model", "--reference-run"})
        if (r->count(name) > 0) run.given.emplace_back(name);
      return orch::cli::run_command(run);
    }
    if (*mb) return orch::cli::map_build_command(build);
    if (*mc) return orch::cli::map_check_command(check);
    if (*mt) return orch::cli::map_traffic_command(traffic);
    if (*bl) return orch::cli::baseline_command(baseline);
    if (*rp) return orch::cli::report_command(report);
    if (const auto code = batch_commands->run()) return *code;
  } catch (const std::exception& e) {
    std::cerr << "orchestrator: " << orch::valid_utf8(e.what()) << "\n";
    return 2;
  }
  return 0;
}
