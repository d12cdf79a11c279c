#include "run/openscenario_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "map/background_traffic.hpp"
#include "map/lane_map.hpp"
#include "opendrive/sumo_lanes.hpp"
#include "opendrive/sumo_net.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/ego_link.hpp"
#include "run/collision_fact.hpp"
#include "run/openscenario_ego_choice.hpp"
#include "run/openscenario_observed.hpp"
#include "run/openscenario_world.hpp"
#include "run/reference_ego_setup.hpp"
#include "run/run_outcome.hpp"
#include "run/run_log.hpp"
#include "run/run_observers.hpp"
#include "run/ssm_device.hpp"
#include "run/storyboard_events.hpp"
#include "run/trace_writer.hpp"

namespace orch {

namespace {

// trace.csv with the columns of ScenarioExecutor runs (TraceWriter::kHeader): x, y are the
// entity's reference point in the OpenDRIVE frame (SUMO's coordinates are the same, the
// conversion keeps them), as SUMO has placed it; actor_id is the entity's name.
class EntityTrace {
 public:
  explicit EntityTrace(const std::filesystem::path& path) : file_(std::fopen(path.c_str(), "w")) {
    if (!file_) throw OrchError(fmt::format("cannot write {}", path.string()));
    fmt::print(file_, "{}\n", TraceWriter::kHeader);
  }
  ~EntityTrace() { std::fclose(file_); }
  EntityTrace(const EntityTrace&) = delete;
  EntityTrace& operator=(const EntityTrace&) = delete;

  // `ego_driver`: the ego's `driver` column (sumo, script or plugin; openscenario_ego.hpp).
  void record(double time, const engine::WorldSnapshot& snap, const OpenScenarioActors& actors, const std::string& ego,
              const char* ego_driver) {
    for (const auto& a : snap.actors) {
      if (!a.present) continue;
      const Vec2 ref = actors.reference_point(a);
      const std::string& name = actors.name_of(a.id);
      fmt::print(file_, "{:.3f},,{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{},0,{}\n", time, name,
                 ref.x(), ref.y(), a.heading, a.speed, a.accel, a.edge, a.lane, a.lane_pos, a.lat_offset.value_or(0.0),
                 a.signals,
                 name == ego ? ego_driver : (actors.is_sumo_driven(name) ? "sumo" : "script"));
      ++rows_;
    }
    if (++steps_ % 200 == 0) std::fflush(file_);
  }
  void flush() { std::fflush(file_); }
  [[nodiscard]] long long rows() const { return rows_; }

 private:
  std::FILE* file_;
  long long rows_ = 0;
  long long steps_ = 0;
};

// --traffic on the converted net: a level or a rate is generated from the net into the run
// folder (the map generator, map/background_traffic.hpp), a route file is used as it is.
std::string traffic_route_file(const RunRequest& req, const std::filesystem::path& net_file, RunResult& result,
                               RunLog& log) {
  const TrafficChoice choice = parse_traffic(req.traffic.empty() ? "none" : req.traffic);
  result.traffic = choice.label;
  std::filesystem::path file;
  switch (choice.kind) {
    case TrafficChoice::Kind::None: return "";
    case TrafficChoice::Kind::File: file = choice.file; break;
    case TrafficChoice::Kind::Rate:
      file = std::filesystem::absolute(req.out_dir / "traffic.rou.xml");
      write_file_atomically(file, background_traffic_xml(net_file, {choice.vehicles_per_hour_per_lane, -1, choice.label}));
      break;
  }
  result.traffic_file = {file.string(), sha256_of_file(file)};
  log.note(fmt::format("background traffic {} ({})", choice.label, file.string()));
  return std::filesystem::absolute(file).string();
}

const engine::ActorState* find_actor(const engine::WorldSnapshot& snap, const OpenScenarioActors& actors,
                                     const std::string& name) {
  for (const auto& a : snap.actors)
    if (actors.name_of(a.id) == name) return &a;
  return nullptr;
}

// The entities SUMO had, for result.json's "actors": what the report draws them with. The
// trace names entities in actor_id, so the report finds a record by its sumo_id (an
// entity's first SUMO id is its name); actor_id here is the run's index of the entity.
std::vector<ActorRecord> entity_records(const OpenScenarioActors& actors) {
  std::vector<ActorRecord> out;
  for (const engine::TrackedActor& t : actors.tracked()) {
    const std::string& name = actors.name_of(t.id);
    out.push_back({static_cast<int>(t.id), name, "", "", "", t.length, t.width, name == actors.ego()});
  }
  std::sort(out.begin(), out.end(), [](const ActorRecord& l, const ActorRecord& r) { return l.id < r.id; });
  return out;
}

// The ego's first collision SUMO reported, if any (its SUMO vehicle: the ego's name, or
// "ego" with an external ego).
std::optional<CollisionFact> ego_collision(const engine::WorldSnapshot& snap, const OpenScenarioActors& actors,
                                           const std::string& ego, double time) {
  if (ego.empty()) return std::nullopt;
  const std::string sumo_id = actors.ego_drive().sumo_id();
  for (const auto& c : snap.collisions)
    if (c.collider == sumo_id || c.victim == sumo_id) {
      const std::string& other = c.collider == sumo_id ? c.victim : c.collider;
      return CollisionFact{other, time, relative_speed(snap, actors.tracked(), sumo_id, other)};
    }
  return std::nullopt;
}

// An external ego needs an ego, and the SUMO id "ego" free for it.
void check_external_ego(const openscenario::Scenario& scenario, const std::string& ego, bool external) {
  if (!external) return;
  if (ego.empty())
    throw ScenarioError(SourceLocation{scenario.file, "/OpenSCENARIO/Entities", 0},
                        "--ego-port: the scenario has no ego (docs/openscenario.md \"The ego\"): "
                        "name it with --ego NAME");
  if (ego != kEgoSumoId && scenario.entity(kEgoSumoId))
    throw ScenarioError(SourceLocation{scenario.file, "/OpenSCENARIO/Entities", 0},
                        fmt::format("--ego-port: the external ego drives the SUMO vehicle \"{}\", but another entity "
                                    "has that name", kEgoSumoId));
}

// The ego's model: --ego-model, or the reference driver when the ego's controller is named so.
EgoModelChoice ego_model_of(const RunRequest& req, const openscenario::Scenario& scenario, const std::string& ego) {
  EgoModelChoice model = req.ego_model;
  const openscenario::Entity* e = ego.empty() ? nullptr : scenario.entity(ego);
  if (e && e->controller && e->controller->name == kR157ControllerName) model.name = "r157";
  return model;
}

// An evaluation file's criteria name entities by their run index (result.json actors[].actor_id)
// or default to the ego; scenes are ScenarioExecutor's. Checked before SUMO starts.
void check_criteria(const EvaluationRequest& ev, const openscenario::Scenario& scenario, const std::string& ego,
                    RunLog& log) {
  const SourceLocation where{ev.file, "/Evaluation/Conditions/Criteria", 0};
  for (const auto& c : ev.criteria) {
    if (c.actor && (*c.actor < 0 || static_cast<std::size_t>(*c.actor) >= scenario.entities.size()))
      throw ScenarioError(where, fmt::format("criterion \"{}\" names actor {}; the OpenSCENARIO file has {} entities "
                                             "(actors 0 to {}, in the order of its Entities)",
                                             c.name, *c.actor, scenario.entities.size(), scenario.entities.size() - 1));
    if (!c.actor && ego.empty() && c.type != "reach_scene")
      throw ScenarioError(where, fmt::format("criterion \"{}\" has no Actor and the scenario has no ego "
                                             "(docs/openscenario.md \"The ego\"): give Actor or --ego", c.name));
    if (c.from_scene || c.to_scene || c.scene)
      throw ScenarioError(where, fmt::format("criterion \"{}\": FromScene, ToScene and Scene are ScenarioExecutor "
                                             "scenes; an OpenSCENARIO run has none (use FromTime/ToTime; reach_scene "
                                             "without Scene holds once the Storyboard's StopTrigger fires)", c.name));
  }
  if (!ev.vehicle_model.empty())
    log.note(fmt::format("VehicleModel {} is not used: OpenSCENARIO entities bring their own vehicles", ev.vehicle_model));
}

}  // namespace

RunResult run_openscenario(const RunRequest& req, Simulator& sim) {
  const auto wall_start = std::chrono::steady_clock::now();
  std::filesystem::create_directories(req.out_dir);
  RunLog log(req.out_dir / "run.log", req.echo);
  RunResult result = new_run_result(req, sim);
  log.note(fmt::format("orchestrator {} | OpenSCENARIO {} | step {} s | seed {} | backend {}", ORCH_VERSION,
                       req.scenario_file, req.step, req.seed, sim.backend()));
  for (const auto& [name, value] : req.parameter_overrides) log.note(fmt::format("--param {}={}", name, value));
  // Declared in this order: the runtime and the actors refer to the roads and lanes.
  std::optional<openscenario::Scenario> scenario;
  std::optional<opendrive::RoadNetwork> roads;
  std::optional<opendrive::SumoLaneIndex> lanes;
  std::optional<openscenario::StoryboardRuntime> runtime;
  std::optional<OpenScenarioActors> actors;
  std::optional<EntityTrace> trace;
  std::optional<LaneMap> sumo_lanes;          // the converted net's lanes, for lane keeping
  std::optional<OpenScenarioRun> observed;    // the run as metrics and criteria see it
  RunObservers observers;                      // metrics.csv, criteria, result.jsonl
  std::optional<std::string> collision;
  std::optional<reference_driver::ReferenceEgo> reference_ego;  // --ego-model r157
  std::optional<reference_driver::EgoWatch> ego_watch;          // the ego's minimum gap and TTC
  EgoModelChoice ego_model;
  std::string ego;
  int background = 0;  // SUMO vehicles that are not entities, at the last step
  try {
    if (req.evaluation) result.evaluation = {req.evaluation->file, sha256_of_file(req.evaluation->file)};
    result.scenario = {req.scenario_file, sha256_of_file(req.scenario_file)};
    scenario.emplace(openscenario::load_scenario(req.scenario_file, {req.parameter_overrides}));
    result.title = std::filesystem::path(req.scenario_file).stem().string();
    result.description = scenario->description;
    if (scenario->road_file.empty())
      throw ScenarioError(SourceLocation{req.scenario_file, "/OpenSCENARIO/RoadNetwork/LogicFile", 0},
                          "an OpenSCENARIO run needs a RoadNetwork LogicFile (an OpenDRIVE road)");
    result.map_id = std::filesystem::path(scenario->road_file).stem().string();
    roads.emplace(opendrive::read_xodr_file(scenario->road_file));
    const opendrive::SumoNet net = opendrive::convert_to_sumo_net(scenario->road_file, opendrive::default_net_cache());
    result.net = {net.net_file.string(), sha256_of_file(net.net_file)};
    log.note(fmt::format("road {} -> SUMO net {} ({})", scenario->road_file, net.net_file.string(),
                         net.from_cache ? "cached" : "converted now"));
    lanes.emplace(*roads, net.net_file.string());
    const EgoChoice chosen = choose_ego(*scenario, req.ego_entity);
    ego = chosen.entity;
    check_external_ego(*scenario, ego, req.ego_link != nullptr);
    ego_model = ego_model_of(req, *scenario, ego);
    if (req.ego_link && ego_model.r157())
      throw OrchError("--ego-port: an external ego drives the ego; the R157 reference driver (--ego-model r157 or "
                      "an R157ReferenceDriver controller) cannot drive it too");
    result.ego_model = ego_model.name;
    log.note(ego.empty() ? fmt::format("no ego: {}", chosen.rule)
             : req.ego_link ? fmt::format("ego {} (SUMO vehicle \"ego\"; driven by SUMO's car-following model until "
                                          "an ActivateControllerAction hands it to the external ego); chosen: {}",
                                          ego, chosen.rule)
                            : fmt::format("ego {} (driven by {}); chosen: {}", ego,
                                          ego_model.r157() ? "the UN R157 reference driver"
                                                           : "SUMO's car-following model",
                                          chosen.rule));
    if (req.evaluation) check_criteria(*req.evaluation, *scenario, ego, log);
    runtime.emplace(*scenario, *roads);
    actors.emplace(*scenario, *lanes, ego, req.ego_link != nullptr);
    sumo_lanes.emplace(LaneMap::build(net.net_file.string(), WaypointFile{}));

    SimulatorConfig config;
    config.net_file = std::filesystem::absolute(net.net_file).string();
    config.step = req.step;
    config.seed = req.seed;
    config.log_file = std::filesystem::absolute(req.out_dir / "sumo.log").string();
    if (const auto traffic = traffic_route_file(req, net.net_file, result, log); !traffic.empty())
      config.route_files.push_back(traffic);
    if (req.ssm && !ego.empty()) {  // the ego is SUMO's (its vehicle id is the entity's name)
      const auto ssm = ssm_device_arguments(ego, req.out_dir / kSsmFileName);
      config.extra_args.insert(config.extra_args.end(), ssm.begin(), ssm.end());
    }
    result.sumo_args = sumo_arguments(config);
    if (req.ego_link) log.note(req.ego_link->listen());
    sim.start(config);
    result.sumo_version = sim.version();
    trace.emplace(req.out_dir / "trace.csv");
    observers.add_measurement(req, *sumo_lanes);
    observed.emplace(*scenario, *roads, *actors);
    observers.begin(*observed);

    std::size_t logged = 0;
    // The reference driver takes the ego once the storyboard has placed it.
    auto drive_ego = [&](std::vector<engine::Command> commands, const engine::WorldSnapshot* snap) {
      if (!ego_watch && !ego.empty()) {
        const auto it = runtime->entities().find(ego);
        if (it != runtime->entities().end() && it->second.placed) {
          reference_ego = reference_ego_for(ego_model, *scenario, *roads, ego, it->second, req.step);
          ego_watch.emplace(lane_path(*roads, it->second), ego, object_kinds(*scenario), 150.0);
        }
      }
      if (ego_watch && snap) ego_watch->step(*snap, actors->tracked());
      if (!reference_ego) return commands;
      reference_ego->observe(commands);
      if (!snap) return commands;
      std::vector<std::string> noticed;
      for (auto& c : reference_ego->drive(*snap, actors->tracked(), noticed)) commands.push_back(std::move(c));
      for (const auto& n : noticed) log.at(snap->time, n);
      return commands;
    };
    sim.apply(drive_ego(actors->place(runtime->entities()), nullptr));
    while (true) {
      // The poses of storyboard time t reach SUMO in this step: the row's time is t.
      sim.advance();
      ++result.steps;
      const double t = runtime->time();
      const engine::WorldSnapshot snap = sim.read(actors->tracked());
      result.sim_time = t;
      background = snap.other_vehicles;
      const auto ego_driver = ego.empty() ? OpenScenarioEgo::Driver::Sumo
                                          : actors->ego_drive().driver(runtime->entities().at(ego));
      const bool model_drives = reference_ego && ego_driver == OpenScenarioEgo::Driver::Sumo;
      trace->record(t, snap, *actors, ego, model_drives ? "r157" : OpenScenarioEgo::label(ego_driver));
      observed->update(snap, t, runtime->entities(), runtime->finished());
      observers.step(StepView{*observed, snap, plugin_driven_actor(req.ego_link, actors->tracked())});
      // Entities SUMO (or the external ego) drove are what the storyboard's conditions see of
      // them from now on; while the storyboard moves the ego laterally, its own state stands.
      for (const std::string& driven : actors->sumo_driven()) {
        if (driven == ego && ego_driver == OpenScenarioEgo::Driver::Storyboard) continue;
        if (const engine::ActorState* e = find_actor(snap, *actors, driven); e && e->present) {
          const Vec2 ref = actors->reference_point(*e);
          runtime->observe(driven, {ref.x(), ref.y(), e->heading}, e->speed, e->accel);
        }
      }
      for (const auto& l = runtime->log(); logged < l.size(); ++logged) {
        result.events.push_back(storyboard_event(l[logged]));
        log.at(l[logged].time, result.events.back().text);
      }
      if (!collision) {
        result.collision = ego_collision(snap, *actors, ego, t);
        if (result.collision) {
          collision = fmt::format("the ego {} collided with {} at t={:.2f} s", ego, result.collision->with, t);
          log.at(t, *collision);
        }
      }
      if (runtime->finished()) {
        result.verdict = Verdict::Success;
        result.reason = fmt::format("the Storyboard's StopTrigger fired at t={:.2f} s", t);
        break;
      }
      if (req.max_time && t >= *req.max_time - 1e-9) {
        result.verdict = Verdict::Failure;
        result.reason = fmt::format("--max-time {} s reached before the Storyboard's StopTrigger", *req.max_time);
        break;
      }
      if (req.interrupted && req.interrupted->load()) {
        result.verdict = Verdict::Error;
        result.reason = fmt::format("interrupted at t={:.3f} s", t);
        break;
      }
      runtime->step(req.step);
      sim.apply(drive_ego(actors->place(runtime->entities()), &snap));
      // The external ego sees this step (a hand-over included) and acts before the world advances.
      if (req.ego_link) req.ego_link->exchange(snap.time);
    }
    log.at(result.sim_time, result.reason);
    if (!result.traffic.empty() && result.traffic != "none")
      log.note(fmt::format("{} background vehicles in SUMO at the end", background));
  } catch (const ScenarioError& e) {
    observers.format_error(req, e.diagnostics());
    record_run_error(result, log);
  } catch (...) {
    record_run_error(result, log);
  }
  if (collision && result.verdict != Verdict::Error) {
    result.reason = result.verdict == Verdict::Success ? *collision + " (" + result.reason + " afterwards)"
                                                : *collision + "; " + result.reason;
    result.verdict = Verdict::Failure;
  }
  if (ego_watch) {
    result.ego_min_gap = ego_watch->exposure().min_gap;
    result.ego_min_ttc = ego_watch->exposure().min_ttc;
  }
  if (actors) result.actors = entity_records(*actors);
  if (observed) result.collisions = observed->contacts();
  observers.finish(req, result);  // metrics; criteria fold into the verdict
  if (trace) {
    trace->flush();
    result.trace_rows = trace->rows();
  }
  if (req.ego_link) {
    req.ego_link->finish(to_string(result.verdict), result.reason);
    result.ego_plugin = req.ego_link->report();
    log.note(describe(*result.ego_plugin));
  }
  sim.close();
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  log.note(fmt::format("verdict {}: {} (simulated {:.2f} s in {} steps)", to_string(result.verdict), result.reason,
                       result.sim_time, result.steps));
  write_result(req.out_dir, result);
  return result;
}

}  // namespace orch
