#include "run/scenario_executor_format.hpp"

#include <fmt/format.h>

#include <optional>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "map/background_traffic.hpp"
#include "map/map_registry.hpp"
#include "map/waypoint_file.hpp"
#include "run/collision_fact.hpp"
#include "run/engine_run.hpp"
#include "run/reference_ego_setup.hpp"
#include "run/ssm_device.hpp"
#include "run/trace_writer.hpp"
#include "run/traffic_trace.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/loader.hpp"
#include "scenario_executor/validator.hpp"

namespace orch {

namespace {

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

class ScenarioExecutorFormat : public RunFormat {
 public:
  explicit ScenarioExecutorFormat(const RunRequest& req) : req_(req) {}

  [[nodiscard]] const char* input_kind() const override { return "scenario"; }

  void open(RunResult& result, RunLog& log, SimulatorConfig& config) override {
    in_.emplace(load_inputs(req_, result, log));
    lanes_.emplace(LaneMap::build(in_->map.net_path().string(), in_->waypoints));
    engine_.emplace(in_->scenario, engine::MapContext{in_->waypoints, *lanes_, in_->map.lane_extension}, in_->catalog,
                    engine::EngineOptions{req_.step, req_.ego_link != nullptr});
    if (req_.evaluation) check_criteria_actors(*req_.evaluation, *engine_);
    log.note(fmt::format("map {} ({}) | {} actors", in_->map.id, in_->map.net_path().string(),
                         engine_->actors().slots().size()));
    observed_.emplace(*engine_);
    // Absolute paths: a SUMO joined with --connect resolves them in its own folder.
    config.net_file = std::filesystem::absolute(in_->map.net_path()).string();
    if (const auto traffic = resolve_traffic(req_, *in_, result, log); !traffic.empty())
      config.route_files.push_back(traffic.string());
    if (req_.ssm) equip_ssm_device(req_, *engine_, config, log);
  }

  void add_observers(RunObservers& observers) override {
    auto trace = std::make_unique<TraceWriter>(req_.out_dir / "trace.csv", *lanes_, *engine_);
    trace_ = trace.get();
    observers.add(std::move(trace));
    observers.add(std::make_unique<TrafficTrace>(req_.out_dir, req_.trace_background));
  }
  [[nodiscard]] const LaneMap& measured_lanes() const override { return *lanes_; }
  [[nodiscard]] const ObservedRun& observed() const override { return *observed_; }

  std::vector<sim::Command> start(RunResult& result, RunLog& log) override {
    engine::StepOutput out = engine_->start();
    log_events(log, result, out.events);
    // The orchestrator's own model (--ego-model r157 or cruise) drives the ego unless a plug-in
    // does; it follows the ego's route, known once the engine has placed it.
    if (!req_.ego_link) reference_ego_ = reference_ego_for(req_.ego_model, *engine_, *lanes_, req_.step);
    if (reference_ego_) {
      log.note(req_.ego_model.cruise()
                   ? "ego driven by the cruise model (--ego-model cruise): its route's speed, no braking for anything"
                   : "ego driven by the UN R157 reference driver (--ego-model r157)");
      trace_->set_model_driven(in_->scenario.ego.id, req_.ego_model.name);
    }
    tracked_ = engine_->tracked();
    return std::move(out.commands);
  }
  [[nodiscard]] const std::vector<sim::TrackedActor>& tracked() const override { return tracked_; }
  std::optional<reference_driver::ReferenceEgo> take_reference_ego() override {
    return std::exchange(reference_ego_, std::nullopt);
  }

  double take_step(const sim::WorldSnapshot& snap, RunResult& result, RunLog& log) override {
    out_ = engine_->step(snap);
    log_events(log, result, out_.events);
    return snap.time;
  }
  std::optional<CollisionFact> ego_collision(const sim::WorldSnapshot& snap, double /*time*/,
                                             RunLog& /*log*/) override {
    return ego_collision_fact(*engine_, in_->scenario.ego.id, snap);
  }
  [[nodiscard]] bool ended() const override { return engine_->state() != engine::RunState::Running; }
  [[nodiscard]] std::string max_time_reason(double max_time) const override {
    return fmt::format("--max-time {} s reached in scene {}", max_time, engine_->scene());
  }
  std::vector<sim::Command> commands(const sim::WorldSnapshot& /*snap*/, RunLog& /*log*/) override {
    return std::move(out_.commands);
  }
  [[nodiscard]] bool reached(const std::string& event) const override {
    if (!engine_ || event.rfind("scene:", 0) != 0) return false;
    for (const auto& v : engine_->visits())
      if (event == fmt::format("scene:{}", v.id)) return true;
    return false;
  }
  void conclude(RunResult& result, RunLog& /*log*/) override {
    switch (engine_->state()) {
      case engine::RunState::EndingReached:
        result.verdict = Verdict::Success;
        result.reason = engine_->end_reason();
        result.ending_scene = engine_->scene();
        break;
      case engine::RunState::StopConditionMet:
        result.verdict = Verdict::Failure;
        result.reason = engine_->end_reason();
        break;
      case engine::RunState::Error:
        result.verdict = Verdict::Error;
        result.reason = engine_->end_reason();
        break;
      case engine::RunState::Running:
        break;  // max time or interrupted: already set
    }
  }

  void finish(RunResult& result) override {
    if (!engine_) return;
    result.scenes = engine_->visits();
    result.collisions = engine_->contacts();
    result.lane_change_conflicts = engine_->lane_change_conflicts();
    result.hand_overs = engine_->hand_overs();
    for (const auto& slot : engine_->actors().slots())
      result.actors.push_back({slot.spec.id, slot.tracked.sumo_id, slot.spec.model_id, slot.spec.description,
                               slot.spec.color, slot.model.length, slot.model.width, slot.is_ego()});
  }
  // A counted contact of the ego fails the test, even when an ending scene was reached
  // afterwards (the run itself went on as scripted).
  [[nodiscard]] std::optional<std::string> ego_collision_reason() const override {
    if (!engine_) return std::nullopt;
    const std::string ego = std::to_string(in_->scenario.ego.id);
    for (const auto& c : engine_->contacts()) {
      if (!c.counted || (c.a != ego && c.b != ego)) continue;
      const std::string other = c.a == ego ? c.b : c.a;
      return fmt::format("the ego collided with {} at t={:.2f} s", engine_->describe_body(other), c.time);
    }
    return std::nullopt;
  }

 private:
  const RunRequest& req_;
  // Declared in this order so that the engine and the trace, which refer to the inputs and
  // lanes, go first.
  std::optional<Inputs> in_;
  std::optional<LaneMap> lanes_;
  std::optional<engine::Engine> engine_;
  std::optional<EngineRun> observed_;  // the engine as the observers see it
  TraceWriter* trace_ = nullptr;       // owned by the loop's observers
  std::vector<sim::TrackedActor> tracked_;
  engine::StepOutput out_;  // the engine's last step: its commands go to SUMO next
  std::optional<reference_driver::ReferenceEgo> reference_ego_;
};

}  // namespace

std::unique_ptr<RunFormat> scenario_executor_format(const RunRequest& request) {
  return std::make_unique<ScenarioExecutorFormat>(request);
}

}  // namespace orch
