// The subcommand registry (cli/subcommand.hpp): validate, run, baseline, map *, report, and
// the list of all subcommands. The batch commands register in cli/batch_commands.cpp.
#include <CLI/CLI.hpp>
#include <memory>

#include "reference_driver/ego_model.hpp"
#include "cli/commands.hpp"
#include "cli/subcommand.hpp"

namespace orch::cli {

namespace {

// SUMO reads its --seed as a 32-bit int; times follow core/plausible.hpp (at most 1e7 s).
const CLI::Range kSeedRange(0LL, 2147483647LL, "SEED");
const CLI::Range kTimeRange(1e-9, 1e7, "SECONDS");

void add_common(CLI::App* app, CommonOptions& c) {
  // One value per --maps, so that `--maps DIR a.json b.json` keeps both files as files.
  app->add_option("--maps", c.map_dirs, "Folder holding map folders (repeatable; default: $ORCH_MAPS, then sumo_nets/)")
      ->allow_extra_args(false);
  app->add_option("--catalog", c.catalog, "Model catalog JSON replacing the built-in one");
}

Handler setup_validate(CLI::App& cmd) {
  auto validate = std::make_shared<ValidateOptions>();
  auto* v = &cmd;
  // No ExistingFile checks on scenario files: a missing or unreadable file is reported like
  // any bad input (validate: INVALID, exit 1; run: result.json with verdict error, exit 2).
  v->add_option("files", validate->files, "Scenario files")->required();
  v->add_flag("--strict", validate->strict, "Treat warnings as errors");
  v->add_flag("-q,--quiet", validate->quiet, "Print only errors and the summary");
  v->add_option("--param", validate->parameters, "NAME=VALUE: set an OpenSCENARIO parameter (repeatable)")
      ->allow_extra_args(false);
  add_common(v, validate->common);
  return [validate] { return validate_command(*validate); };
}

Handler setup_run(CLI::App& cmd) {
  auto run = std::make_shared<RunOptions>();
  auto* r = &cmd;
  r->add_option("file", run->file, "Scenario file")->required();
  r->add_option("--out", run->out, "Output folder (result.json, trace.csv, run.log)")->capture_default_str();
  r->add_option("--step", run->step, "Simulation step, s")->capture_default_str()->check(CLI::Range(0.001, 1.0));
  r->add_option("--seed", run->seed, "Random seed for SUMO")->capture_default_str()->check(kSeedRange);
  r->add_option("--max-time", run->max_time, "End the run (verdict failure) at this simulation time, s")
      ->check(kTimeRange);
  r->add_flag("--strict", run->strict, "Refuse to run a scenario with validation warnings");
  r->add_flag("-q,--quiet", run->quiet, "Do not echo the run log to the terminal");
  r->add_option("--ego-port", run->ego_port,
                "An external plug-in drives the ego over TraCI: listen on this port (0: any free port)")
      ->check(CLI::Range(0, 65535));
  r->add_option("--ego", run->ego_entity,
                "OpenSCENARIO runs: the entity that is the ego, driven by SUMO (or --ego-model, --ego-port) instead of "
                "the storyboard (default: the entity with a system-under-test controller drives; docs/openscenario.md "
                "\"The ego\")");
  r->add_option("--param", run->parameters, "NAME=VALUE: set an OpenSCENARIO parameter (repeatable)")
      ->allow_extra_args(false);
  r->add_option("--ego-model", run->ego_model,
                "What drives the ego when no plug-in does: sumo (SUMO's car-following model, default), r157 (the UN "
                "R157 reference driver, docs/reference-driver.md) or cruise (keeps its set speed, brakes for nothing: a "
                "system under test that does not react)")
      ->check(CLI::IsMember(ego_model_names()));
  r->add_flag("--reference-run", run->reference_run,
              "Run the scenario again with the R157 reference driver (into reference/) and judge whether a collision "
              "was preventable");
  r->add_option("--controllers", run->controllers,
                "OpenSCENARIO runs: off runs no controller (esmini's --disable_controllers): every entity, the ego too, "
                "follows the storyboard; controllers are read and checked, Activate/AssignControllerActions are logged "
                "and hand nobody to SUMO. Not with --ego-model, --ego-port or --reference-run (default: on)")
      ->check(CLI::IsMember({"on", "off"}));
  r->add_option("--ego-address", run->ego_address, "Address the ego TraCI server listens on")->capture_default_str();
  r->add_option("--ego-wait", run->ego_wait, "Seconds to wait for the ego plug-in to connect")
      ->capture_default_str()->check(kTimeRange);
  r->add_option("--ego-timeout", run->ego_timeout, "Seconds the world waits for the ego plug-in's next message")
      ->capture_default_str()->check(kTimeRange);
  r->add_option("--traffic", run->traffic,
                "Background traffic: none, light, medium, dense, vehicles per hour and lane, or a SUMO route file "
                "(default: the scenario's own \"traffic\", else none)");
  r->add_flag("--trace-background", run->trace_background, "Write background.csv: background vehicles near the actors");
  r->add_flag("--no-report", run->no_report, "Do not write report.html");
  r->add_flag("--video", run->video, "Write video.mp4: the run replayed in sumo-gui (under Xvfb without a display)");
  r->add_option("--backend", run->backend, "SUMO client library: libsumo (in-process, default) or traci")
      ->check(CLI::IsMember({"libsumo", "traci"}));
  r->add_flag("--gui", run->gui, "Watch the run in sumo-gui (traci backend)");
  r->add_option("--connect", run->connect, "Use a SUMO already running with --remote-port, at HOST:PORT (traci backend)");
  r->add_option("--realtime", run->realtime, "Advance at most FACTOR times as fast as wall-clock time (1 = real time)")
      ->check(CLI::Range(1e-6, 1e6));
  r->add_option("--sumo-timeout", run->sumo_timeout,
                "Seconds without an answer from SUMO before the run ends as an error (traci backend; 0: no limit)")
      ->capture_default_str()->check(CLI::Range(0.0, 1e7));
  r->add_option("--jsonl-every", run->jsonl_every, "Evaluation files: a result.jsonl frame line every N steps")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  r->add_flag("--ssm", run->ssm, "Equip the ego (when SUMO drives it) with SUMO's SSM device: ssm.xml in the run folder");
  r->add_option("--fork-with", run->fork_with,
                "Another variant of the scenario (repeatable, each with its --fork-out): the variants share their common "
                "prefix, run once (libsumo; docs/forking.md)")
      ->allow_extra_args(false);
  r->add_option("--fork-out", run->fork_out, "Output folder of the --fork-with variant in the same place")
      ->allow_extra_args(false);
  r->add_option("--fork-at", run->fork_at,
                "With --fork-with: every variant continues in a process of its own from this SUMO time (s) on, or "
                "from the step an event happens (scene:N entered, a storyboard element of that name started); "
                "variants that part earlier still part where they part, with a warning in fork.json");
  r->add_option("--fork-param", run->fork_params,
                "K:NAME=VALUE: the K-th --fork-with variant (1-based) runs with --param NAME=VALUE instead of the "
                "first run's value (OpenSCENARIO; repeatable)")
      ->allow_extra_args(false);
  add_common(r, run->common);
  return [run, r] {
    for (const char* name : {"--step", "--seed", "--max-time", "--traffic", "--backend", "--ego-model", "--reference-run"})
      if (r->count(name) > 0) run->given.emplace_back(name);
    return run_command(*run);
  };
}

Handler setup_baseline(CLI::App& cmd) {
  auto baseline = std::make_shared<BaselineOptions>();
  auto* bl = &cmd;
  bl->add_option("map", baseline->map, "Map id or folder, or a SUMO net file (NAME.net.xml)")->required();
  bl->add_option("--traffic", baseline->traffic, "Background traffic, as for run")->capture_default_str();
  bl->add_option("--steps", baseline->steps, "Simulation steps")->capture_default_str()->check(CLI::PositiveNumber);
  bl->add_option("--step", baseline->step, "Simulation step, s")->capture_default_str()->check(CLI::Range(0.001, 1.0));
  bl->add_option("--seed", baseline->seed, "Random seed for SUMO")->capture_default_str()->check(kSeedRange);
  bl->add_option("--backend", baseline->backend, "libsumo or traci")->capture_default_str()
      ->check(CLI::IsMember({"libsumo", "traci"}));
  bl->add_option("--out", baseline->out, "Folder for sumo.log")->capture_default_str();
  add_common(bl, baseline->common);
  return [baseline] { return baseline_command(*baseline); };
}

Handler setup_map_build(CLI::App& cmd) {
  auto build = std::make_shared<MapBuildOptions>();
  auto* mb = &cmd;
  mb->add_option("maps", build->maps, "Map ids or folders to rebuild (default with no --waypoints: all)");
  mb->add_option("--waypoints", build->waypoints, "Build a new map from this RoadEditor waypoint file")
      ->check(CLI::ExistingFile);
  mb->add_option("--id", build->id, "Id of the new map (default: the waypoint file's mapId)");
  mb->add_option("--alias", build->aliases, "Extra name scenarios may use for the new map (repeatable)");
  mb->add_option("--out", build->out, "Folder of the new map (default: sumo_nets/<id>)");
  add_common(mb, build->common);
  return [build] { return map_build_command(*build); };
}

Handler setup_map_check(CLI::App& cmd) {
  auto check = std::make_shared<MapCheckOptions>();
  auto* mc = &cmd;
  mc->add_option("maps", check->maps, "Map ids or folders (default: all)");
  mc->add_option("--tolerance", check->tolerance, "Largest acceptable distance, m")->capture_default_str();
  add_common(mc, check->common);
  return [check] { return map_check_command(*check); };
}

Handler setup_map_traffic(CLI::App& cmd) {
  auto traffic = std::make_shared<MapTrafficOptions>();
  auto* mt = &cmd;
  mt->add_option("maps", traffic->maps, "Map ids or folders (default: all)");
  mt->add_option("--rate", traffic->rate, "Write one file at this many vehicles per hour and lane (with --out)")
      ->check(CLI::NonNegativeNumber);
  mt->add_option("--fill-per-km", traffic->fill_per_km,
                 "With --rate: vehicles per km and lane placed at the start (default: the rate's steady state)");
  mt->add_option("--out", traffic->out, "File for --rate");
  add_common(mt, traffic->common);
  return [traffic] { return map_traffic_command(*traffic); };
}

Handler setup_report(CLI::App& cmd) {
  auto report = std::make_shared<ReportOptions>();
  cmd.add_option("dirs", report->dirs, "Run folders (with result.json) or batch folders (with batch.json)")
      ->required()->check(CLI::ExistingDirectory);
  return [report] { return report_command(*report); };
}

}  // namespace

std::vector<Subcommand> scenario_subcommands() {
  return {{{"validate"}, "Check scenario files without running them", setup_validate},
          {{"run"}, "Run one scenario on SUMO", setup_run},
          {{"baseline"}, "Run a map's background traffic in SUMO alone, without a scenario", setup_baseline}};
}

std::vector<Subcommand> map_subcommands() {
  return {{{"map"}, "Build and check SUMO networks for RoadEditor maps", nullptr},
          {{"map", "build"}, "Generate the SUMO net of a map from its waypoint file", setup_map_build},
          {{"map", "check"}, "Print, per route, the largest waypoint-to-lane-centre distance", setup_map_check},
          {{"map", "traffic"}, "Generate the background traffic files of maps (traffic/<level>.rou.xml)",
           setup_map_traffic}};
}

std::vector<Subcommand> report_subcommands() {
  return {{{"report"}, "Write report.html of run folders and batch folders again", setup_report}};
}

std::vector<Subcommand> subcommands() {
  std::vector<Subcommand> all;
  for (auto part : {scenario_subcommands(), map_subcommands(), report_subcommands(), batch_subcommands()})
    all.insert(all.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
  return all;
}

}  // namespace orch::cli
