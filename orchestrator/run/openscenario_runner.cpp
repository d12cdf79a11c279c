#include "run/openscenario_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "map/background_traffic.hpp"
#include "opendrive/sumo_lanes.hpp"
#include "opendrive/sumo_net.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/openscenario_world.hpp"
#include "run/run_outcome.hpp"
#include "run/run_log.hpp"
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

  void record(double time, const engine::WorldSnapshot& snap, const OpenScenarioActors& actors) {
    for (const auto& a : snap.actors) {
      if (!a.present) continue;
      const Vec2 ref = actors.reference_point(a);
      const std::string& name = actors.name_of(a.id);
      fmt::print(file_, "{:.3f},,{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{},0,{}\n", time, name,
                 ref.x(), ref.y(), a.heading, a.speed, a.accel, a.edge, a.lane, a.lane_pos, a.lat_offset.value_or(0.0),
                 a.signals, actors.is_sumo_driven(name) ? "sumo" : "script");
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

// The ego's first collision SUMO reported, if any.
std::optional<std::string> ego_collision(const engine::WorldSnapshot& snap, const std::string& ego, double time) {
  if (ego.empty()) return std::nullopt;
  for (const auto& c : snap.collisions)
    if (c.collider == ego || c.victim == ego)
      return fmt::format("the ego {} collided with {} at t={:.2f} s", ego, c.collider == ego ? c.victim : c.collider,
                         time);
  return std::nullopt;
}

}  // namespace

RunResult run_openscenario(const RunRequest& req, Simulator& sim) {
  std::filesystem::create_directories(req.out_dir);
  RunLog log(req.out_dir / "run.log", req.echo);
  RunResult result = new_run_result(req, sim);
  log.note(fmt::format("orchestrator {} | OpenSCENARIO {} | step {} s | seed {} | backend {}", ORCH_VERSION,
                       req.scenario_file, req.step, req.seed, sim.backend()));
  // Declared in this order: the runtime and the actors refer to the roads and lanes.
  std::optional<openscenario::Scenario> scenario;
  std::optional<opendrive::RoadNetwork> roads;
  std::optional<opendrive::SumoLaneIndex> lanes;
  std::optional<openscenario::StoryboardRuntime> runtime;
  std::optional<OpenScenarioActors> actors;
  std::optional<EntityTrace> trace;
  std::optional<std::string> collision;
  std::string ego;
  int background = 0;  // SUMO vehicles that are not entities, at the last step
  try {
    if (req.ego_link)
      throw OrchError("--ego-port: an external ego is not supported for OpenSCENARIO runs yet (docs/openscenario.md)");
    result.scenario = {req.scenario_file, sha256_of_file(req.scenario_file)};
    scenario.emplace(openscenario::load_scenario(req.scenario_file));
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
    ego = choose_ego_entity(*scenario, req.ego_entity);
    log.note(ego.empty() ? std::string("no ego (no entity with the ALKSController controller, no --ego)")
                         : fmt::format("ego {} (driven by SUMO's car-following model)", ego));
    runtime.emplace(*scenario, *roads);
    actors.emplace(*scenario, *lanes, ego);

    SimulatorConfig config;
    config.net_file = std::filesystem::absolute(net.net_file).string();
    config.step = req.step;
    config.seed = req.seed;
    config.log_file = std::filesystem::absolute(req.out_dir / "sumo.log").string();
    if (const auto traffic = traffic_route_file(req, net.net_file, result, log); !traffic.empty())
      config.route_files.push_back(traffic);
    result.sumo_args = sumo_arguments(config);
    sim.start(config);
    result.sumo_version = sim.version();
    trace.emplace(req.out_dir / "trace.csv");

    std::size_t logged = 0;
    sim.apply(actors->place(runtime->entities()));
    while (true) {
      // The poses of storyboard time t reach SUMO in this step: the row's time is t.
      sim.advance();
      ++result.steps;
      const double t = runtime->time();
      const engine::WorldSnapshot snap = sim.read(actors->tracked());
      result.sim_time = t;
      background = snap.other_vehicles;
      trace->record(t, snap, *actors);
      // Entities SUMO drove (the ego, activated controllers) are what the storyboard's
      // conditions see of them from now on.
      for (const std::string& driven : actors->sumo_driven())
        if (const engine::ActorState* e = find_actor(snap, *actors, driven); e && e->present) {
          const Vec2 ref = actors->reference_point(*e);
          runtime->observe(driven, {ref.x(), ref.y(), e->heading}, e->speed, e->accel);
        }
      for (const auto& l = runtime->log(); logged < l.size(); ++logged)
        log.at(l[logged].time, fmt::format("{} {} {}", l[logged].type, l[logged].name, l[logged].transition));
      if (!collision) {
        collision = ego_collision(snap, ego, t);
        if (collision) log.at(t, *collision);
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
      sim.apply(actors->place(runtime->entities()));
    }
    log.at(result.sim_time, result.reason);
    if (!result.traffic.empty() && result.traffic != "none")
      log.note(fmt::format("{} background vehicles in SUMO at the end", background));
  } catch (...) {
    record_run_error(result, log);
  }
  if (collision && result.verdict != Verdict::Error) {
    result.reason = result.verdict == Verdict::Success ? *collision + " (" + result.reason + " afterwards)"
                                                : *collision + "; " + result.reason;
    result.verdict = Verdict::Failure;
  }
  if (actors) result.actors = entity_records(*actors);
  if (trace) {
    trace->flush();
    result.trace_rows = trace->rows();
  }
  sim.close();
  log.note(fmt::format("verdict {}: {} (simulated {:.2f} s in {} steps)", to_string(result.verdict), result.reason,
                       result.sim_time, result.steps));
  write_result(req.out_dir, result);
  return result;
}

}  // namespace orch
