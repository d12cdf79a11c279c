// orchestrator: runs ScenarioExecutor scenarios on SUMO. See README.md.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/commands.hpp"

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
  v->add_option("files", validate.files, "Scenario files")->required()->check(CLI::ExistingFile);
  v->add_flag("--strict", validate.strict, "Treat warnings as errors");
  v->add_flag("-q,--quiet", validate.quiet, "Print only errors and the summary");
  add_common(v, validate.common);

  orch::cli::RunOptions run;
  auto* r = app.add_subcommand("run", "Run one scenario on SUMO");
  r->add_option("file", run.file, "Scenario file")->required()->check(CLI::ExistingFile);
  r->add_option("--out", run.out, "Output folder (result.json, trace.csv, run.log)")->capture_default_str();
  r->add_option("--step", run.step, "Simulation step, s")->capture_default_str()->check(CLI::Range(0.001, 1.0));
  r->add_option("--seed", run.seed, "Random seed for SUMO")->capture_default_str();
  r->add_option("--max-time", run.max_time, "End the run (verdict failure) at this simulation time, s")
      ->check(CLI::PositiveNumber);
  r->add_flag("--strict", run.strict, "Refuse to run a scenario with validation warnings");
  r->add_flag("-q,--quiet", run.quiet, "Do not echo the run log to the terminal");
  add_common(r, run.common);

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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*v) return orch::cli::validate_command(validate);
    if (*r) return orch::cli::run_command(run);
    if (*mb) return orch::cli::map_build_command(build);
    if (*mc) return orch::cli::map_check_command(check);
  } catch (const std::exception& e) {
    std::cerr << "orchestrator: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
