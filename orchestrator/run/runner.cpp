#include "run/runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/scenario_format.hpp"
#include "engine/engine.hpp"
#include "map/background_traffic.hpp"
#include "map/lane_map.hpp"
#include "map/map_registry.hpp"
#include "map/waypoint_file.hpp"
#include "run/ego_link.hpp"
#include "run/engine_run.hpp"
#include "run/collision_fact.hpp"
#include "run/openscenario_runner.hpp"
#include "run/reference_ego_setup.hpp"
#include "run/run_outcome.hpp"
#include "run/run_log.hpp"
#include "run/run_observers.hpp"
#include "run/ssm_device.hpp"
#include "run/trace_writer.hpp"
#include "run/traffic_trace.hpp"
#include "scenario/catalog.hpp"
#include "scenario/loader.hpp"
#include "scenario/validator.hpp"

namespace orch {

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point from, Clock::time_point to) { return std::chrono::duration<double>(to - from).count(); }
double seconds_since(Clock::time_point t) { return seconds(t, Clock::now()); }

// Everything a run needs from disk, loaded and checked before SUMO starts.
struct Inputs {
  scenario::Scenario scenario;
  MapManifest map;
  WaypointFile waypoints;
  Catalog catalog;
};

Inputs load_inputs(const RunRequest& req, RunResult& result, RunLog& log) {
  LoadedScenario loaded = load_scenario(req.scenario_file);
  result.scenario = {req.scenario_file, sha256_of_file(req.scenario_file)};
  if (!loaded.scenario) throw ScenarioError(loaded.diagnostics);
  scenario::Scenario s = std::move(*loaded.scenario);
  if (req.evaluation && !req.evaluation->vehicle_model.empty()) s.ego.model_id = req.evaluation->vehicle_model;
  result.title = s.title;
  result.description = s.description;
  result.map_id = s.map_id;

  const auto dirs = req.map_dirs.empty() ? MapRegistry::default_search_dirs() : req.map_dirs;
  const MapRegistry registry(dirs);
  const MapManifest* map = registry.find(s.map_id);
  if (!map) throw MapError(fmt::format("no map \"{}\" (scenario map_id) in {} map folder(s)", s.map_id, dirs.size()));
  WaypointFile waypoints = load_waypoint_file(map->waypoint_path().string());
  result.waypoints = {map->waypoint_path().string(), sha256_of_file(map->waypoint_path())};
  result.net = {map->net_path().string(), sha256_of_file(map->net_path())};
  Catalog catalog = req.catalog_file.empty() ? Catalog::embedded() : Catalog::load(req.catalog_file);

  Diagnostics diags = loaded.diagnostics;
  diags.append(check_scenario(s, waypoints, catalog, ValidationOptions{req.strict}));
  for (const auto& d : diags.items()) {
    if (d.severity == Severity::Warning) result.warnings.push_back(d.format());
    log.note(d.format());
  }
  if (diags.has_errors()) throw ScenarioError(diags);
  if (req.strict && diags.warning_count() > 0)
    throw ScenarioError(SourceLocation{req.scenario_file, "", 0},
                        fmt::format("{} validation warning(s) and --strict", diags.warning_count()));
  return Inputs{std::move(s), *map, std::move(waypoints), std::move(catalog)};
}

void log_events(RunLog& log, RunResult& result, const std::vector<engine::Event>& events) {
  for (const auto& e : events) {
    log.at(e.time, e.text);
    result.events.push_back(e);
  }
}

// The run's background traffic: --traffic, else the scenario's own "traffic" (a route file
// beside the scenario file, or a level), else none. Returns its route file (empty: none).
std::filesystem::path resolve_traffic(const RunRequest& req, const Inputs& in, RunResult& result, RunLog& log) {
  std::string text = req.traffic;
  if (text.empty() && !in.scenario.traffic.empty()) {
    text = in.scenario.traffic;
    const auto beside = std::filesystem::path(req.scenario_file).parent_path() / text;
    if (std::filesystem::is_regular_file(beside)) text = beside.string();
  }
  const TrafficChoice choice = parse_traffic(text);
  result.traffic = choice.label;
  const auto file = traffic_file_for_run(choice, in.map, req.out_dir);
  if (file.empty()) return file;
  result.traffic_file = {file.string(), sha256_of_file(file)};
  log.note(fmt::format("background traffic {} ({})", choice.label, file.string()));
  return file;
}

// A collision involving the ego fails the test even when an ending scene was reached
// afterwards (the run itself went on as scripted). Errors stay errors.
void judge_collisions(const engine::Engine& engine, scenario::ActorId ego, RunResult& result) {
  if (result.verdict == Verdict::Error) return;
  for (const auto& c : engine.contacts()) {
    if (!c.counted || (c.a != std::to_string(ego) && c.b != std::to_string(ego))) continue;
    const std::string other = c.a == std::to_string(ego) ? c.b : c.a;
    const std::string what = fmt::format("the ego collided with {} at t={:.2f} s", engine.describe_body(other), c.time);
    result.reason = result.verdict == Verdict::Success ? what + " (" + result.reason + " afterwards)" : what + "; " + result.reason;
    result.verdict = Verdict::Failure;
    return;
  }
}

// Criteria name actors of the scenario: checked before SUMO starts.
void check_criteria_actors(const EvaluationRequest& ev, const engine::Engine& engine) {
  for (const auto& c : ev.criteria)
    if (c.actor && !engine.actors().find(*c.actor))
      throw ScenarioError(SourceLocation{ev.file, "", 0},
                          fmt::format("criterion \"{}\" names actor {}, which the scenario does not have", c.name, *c.actor));
}

// --ssm: SUMO's own SSM device on the ego, when SUMO drives it.
void equip_ssm_device(const RunRequest& req, const engine::Engine& engine, SimulatorConfig& config, RunLog& log) {
  if (req.ego_link) {
    log.note("--ssm: the ego is driven by the plug-in, not by SUMO: no SSM device");
    return;
  }
  for (const auto& slot : engine.actors().slots())
    if (slot.is_ego()) {
      const auto args = ssm_device_arguments(slot.tracked.sumo_id, req.out_dir / kSsmFileName);
      config.extra_args.insert(config.extra_args.end(), args.begin(), args.end());
      log.note(fmt::format("--ssm: SUMO's SSM device on the ego ({}) writes {}", slot.tracked.sumo_id, kSsmFileName));
    }
}

}  // namespace

RunResult run_scenario(const RunRequest& req, Simulator& sim) {
  // The one place where the language picks the runtime (the content decides, not the name).
  if (detect_scenario_format(req.scenario_file) == ScenarioFormat::OpenScenario) return run_openscenario(req, sim);
  const auto wall_start = Clock::now();
  std::optional<Clock::time_point> loop_start, loop_end;
  std::filesystem::create_directories(req.out_dir);
  RunLog log(req.out_dir / "run.log", req.echo);
  RunResult result = new_run_result(req, sim);
  log.note(fmt::format("orchestrator {} | scenario {} | step {} s | seed {} | backend {}", ORCH_VERSION,
                       req.scenario_file, req.step, req.seed, sim.backend()));

  // Declared in this order so that the engine and the trace, which refer to the inputs and
  // lanes, go first.
  std::optional<Inputs> in;
  std::optional<LaneMap> lanes;
  std::optional<engine::Engine> engine;
  std::optional<EngineRun> observed;  // the engine as the observers see it
  // The step loop's observers (run_observer.hpp), in the order they see each step.
  RunObservers observers;
  try {
    if (req.evaluation) result.evaluation = {req.evaluation->file, sha256_of_file(req.evaluation->file)};
    in.emplace(load_inputs(req, result, log));
    lanes.emplace(LaneMap::build(in->map.net_path().string(), in->waypoints));
    engine.emplace(in->scenario, engine::MapContext{in->waypoints, *lanes, in->map.lane_extension}, in->catalog,
                   engine::EngineOptions{req.step, req.ego_link != nullptr});
    if (req.evaluation) check_criteria_actors(*req.evaluation, *engine);
    log.note(fmt::format("map {} ({}) | {} actors", in->map.id, in->map.net_path().string(),
                         engine->actors().slots().size()));

    SimulatorConfig config;
    // Absolute paths: a SUMO joined with --connect resolves them in its own folder.
    config.net_file = std::filesystem::absolute(in->map.net_path()).string();
    config.step = req.step;
    config.seed = req.seed;
    config.log_file = std::filesystem::absolute(req.out_dir / "sumo.log").string();
    if (const auto traffic = resolve_traffic(req, *in, result, log); !traffic.empty())
      config.route_files.push_back(traffic.string());
    if (req.ssm) equip_ssm_device(req, *engine, config, log);
    result.sumo_args = sumo_arguments(config);
    if (req.ego_link) log.note(req.ego_link->listen());
    sim.start(config);
    result.sumo_version = sim.version();
    auto trace = std::make_unique<TraceWriter>(req.out_dir / "trace.csv", *lanes, *engine);
    TraceWriter& trace_writer = *trace;
    observers.add(std::move(trace));
    observers.add(std::make_unique<TrafficTrace>(req.out_dir, req.trace_background));
    observers.add_measurement(req, *lanes);
    observed.emplace(*engine);
    observers.begin(*observed);

    auto out = engine->start();
    log_events(log, result, out.events);
    // The R157 reference driver drives the ego unless a plug-in does (--ego-model r157); it
    // follows the ego's route, known once the engine has placed it.
    std::optional<reference_driver::ReferenceEgo> reference_ego;
    if (!req.ego_link) reference_ego = reference_ego_for(req.ego_model, *engine, *lanes, req.step);
    if (reference_ego) {
      log.note("ego driven by the UN R157 reference driver (--ego-model r157)");
      trace_writer.set_model_driven(in->scenario.ego.id, "r157");
      reference_ego->observe(out.commands);
    }
    sim.apply(out.commands);
    const auto tracked = engine->tracked();
    loop_start = Clock::now();
    while (true) {
      const auto before_step = Clock::now();
      sim.advance();
      result.timing.sumo_step_s += seconds_since(before_step);
      ++result.steps;
      const engine::WorldSnapshot snap = sim.read(tracked);
      out = engine->step(snap);
      result.sim_time = snap.time;
      if (!result.collision) result.collision = ego_collision_fact(*engine, in->scenario.ego.id, snap);
      log_events(log, result, out.events);
      observers.step(StepView{*observed, snap, plugin_driven_actor(req.ego_link, tracked)});
      if (engine->state() != engine::RunState::Running) break;
      if (req.max_time && snap.time >= *req.max_time - 1e-9) {
        result.verdict = Verdict::Failure;
        result.reason = fmt::format("--max-time {} s reached in scene {}", *req.max_time, engine->scene());
        log.at(snap.time, result.reason);
        break;
      }
      if (req.interrupted && req.interrupted->load()) {
        result.verdict = Verdict::Error;
        result.reason = fmt::format("interrupted at t={:.3f} s", snap.time);
        log.at(snap.time, result.reason);
        break;
      }
      if (reference_ego) {
        reference_ego->observe(out.commands);
        std::vector<std::string> noticed;
        for (auto& c : reference_ego->drive(snap, tracked, noticed)) out.commands.push_back(std::move(c));
        for (const auto& n : noticed) log.at(snap.time, n);
      }
      sim.apply(out.commands);
      // The plug-in sees this step (a hand_over included) and acts before the world advances.
      if (req.ego_link) {
        const auto before_plugin = Clock::now();
        req.ego_link->exchange(snap.time);
        result.timing.plugin_s += seconds_since(before_plugin);
      }
    }
    loop_end = Clock::now();
    switch (engine->state()) {
      case engine::RunState::EndingReached:
        result.verdict = Verdict::Success;
        result.reason = engine->end_reason();
        result.ending_scene = engine->scene();
        break;
      case engine::RunState::StopConditionMet:
        result.verdict = Verdict::Failure;
        result.reason = engine->end_reason();
        break;
      case engine::RunState::Error:
        result.verdict = Verdict::Error;
        result.reason = engine->end_reason();
        break;
      case engine::RunState::Running:
        break;  // max time or interrupted: already set
    }
  } catch (const ScenarioError& e) {
    observers.format_error(req, e.diagnostics());
    record_run_error(result, log);
  } catch (...) {
    record_run_error(result, log);
  }
  if (loop_start && !loop_end) loop_end = Clock::now();  // the loop ended by an exception
  if (engine) {
    result.scenes = engine->visits();
    result.collisions = engine->contacts();
    result.lane_change_conflicts = engine->lane_change_conflicts();
    result.hand_overs = engine->hand_overs();
    for (const auto& slot : engine->actors().slots())
      result.actors.push_back({slot.spec.id, slot.tracked.sumo_id, slot.spec.model_id, slot.spec.description,
                               slot.spec.color, slot.model.length, slot.model.width, slot.is_ego()});
    judge_collisions(*engine, in->scenario.ego.id, result);
  }
  observers.finish(req, result);
  if (req.ego_link) {
    req.ego_link->finish(to_string(result.verdict), result.reason);
    result.ego_plugin = req.ego_link->report();
    log.note(describe(*result.ego_plugin));
  }
  sim.close();
  result.wall_time_s = seconds_since(wall_start);
  if (!loop_start) loop_start = Clock::now();  // it never got to the first step
  if (!loop_end) loop_end = *loop_start;
  result.timing.start_s = seconds(wall_start, *loop_start);
  result.timing.orchestrator_s =
      std::max(0.0, seconds(*loop_start, *loop_end) - result.timing.sumo_step_s - result.timing.plugin_s);
  result.timing.finish_s = std::max(0.0, result.wall_time_s - seconds(wall_start, *loop_end));
  log.note(fmt::format("verdict {}: {} (simulated {:.2f} s in {} steps, {:.2f} s wall)", to_string(result.verdict),
                       result.reason, result.sim_time, result.steps, result.wall_time_s));
  write_result(req.out_dir, result);
  return result;
}

}  // namespace orch
