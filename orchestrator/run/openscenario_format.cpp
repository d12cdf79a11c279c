#include "run/openscenario_format.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <set>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "map/background_traffic.hpp"
#include "map/lane_map.hpp"
#include "opendrive/sumo_lanes.hpp"
#include "opendrive/sumo_net.hpp"
#include "opendrive/sumo_signals.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/synchronize_targets.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/collision_fact.hpp"
#include "run/ego_link.hpp"
#include "run/entity_trace.hpp"
#include "run/openscenario_ego_choice.hpp"
#include "run/openscenario_observed.hpp"
#include "run/openscenario_signals.hpp"
#include "run/openscenario_traffic.hpp"
#include "run/traffic_actions_trace.hpp"
#include "run/traffic_trace.hpp"
#include "run/openscenario_world.hpp"
#include "run/reference_ego_setup.hpp"
#include "run/roadless_net.hpp"
#include "run/ssm_device.hpp"
#include "run/storyboard_events.hpp"

namespace orch {

namespace {

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

const sim::ActorState* find_actor(const sim::WorldSnapshot& snap, const OpenScenarioActors& actors,
                                     const std::string& name) {
  for (const auto& a : snap.actors)
    if (actors.name_of(a.id) == name) return &a;
  return nullptr;
}

// The entities SUMO had, for result.json's "actors": what the report draws them with. The
// trace names entities in actor_id, so the report finds a record by its sumo_id (an
// entity's first SUMO id is its name); actor_id here is the run's index of the entity.
// The ego's description says who drove it and why (the report shows it beside its name).
std::vector<ActorRecord> entity_records(const OpenScenarioActors& actors, const std::string& ego_summary) {
  std::vector<ActorRecord> out;
  for (const sim::TrackedActor& t : actors.tracked()) {
    const std::string& name = actors.name_of(t.id);
    const bool ego = name == actors.ego();
    out.push_back({static_cast<int>(t.id), name, "", ego ? ego_summary : "", "", t.length, t.width, ego});
  }
  std::sort(out.begin(), out.end(), [](const ActorRecord& l, const ActorRecord& r) { return l.id < r.id; });
  return out;
}

// The ego's first collision SUMO reported, if any (its SUMO vehicle: the ego's name, or
// "ego" with an external ego).
std::optional<CollisionFact> sumo_ego_collision(const sim::WorldSnapshot& snap, const OpenScenarioActors& actors,
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
// --controllers off leaves the ego to the storyboard: whatever asks for something to drive it
// contradicts it (the command line's options, or an evaluation file's EgoModel / ReferenceRun /
// no_preventable_collision criterion). --ego NAME does not: it only names the ego then.
void check_controllers_off(const RunRequest& req) {
  std::vector<std::string> drivers;
  if (req.ego_link) drivers.emplace_back("--ego-port (a plug-in drives the ego)");
  if (req.ego_model_given) drivers.push_back("--ego-model " + req.ego_model.name + " (or the evaluation file's EgoModel)");
  if (req.reference_run)
    drivers.emplace_back("--reference-run (or the evaluation file's ReferenceRun / a no_preventable_collision criterion)");
  if (drivers.empty()) return;
  throw OrchError(fmt::format("--controllers off: every entity follows the storyboard, nothing drives the ego; it "
                              "contradicts {}: give one or the other", fmt::join(drivers, " and ")));
}

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

class OpenScenarioFormat : public RunFormat {
 public:
  explicit OpenScenarioFormat(const RunRequest& req) : req_(req) {}

  [[nodiscard]] const char* input_kind() const override { return "OpenSCENARIO"; }
  void note_settings(RunLog& log) const override {
    for (const auto& [name, value] : req_.parameter_overrides) log.note(fmt::format("--param {}={}", name, value));
  }

  void open(RunResult& result, RunLog& log, SimulatorConfig& config) override;

  void add_observers(RunObservers& observers) override {
    observers.add(std::make_unique<EntityTrace>(req_.out_dir / "trace.csv", *actors_, *roads_, [this] { return ego_label_; }));
    // The TrafficActions' vehicles (traffic_actions.csv), and as in ScenarioExecutor runs the
    // background's counts (counts.csv) and, with --trace-background, its vehicles (background.csv).
    observers.add(std::make_unique<TrafficActionsTrace>(
        req_.out_dir, [this]() -> const openscenario::TrafficBook* { return runtime_ ? &runtime_->traffic() : nullptr; }));
    observers.add(std::make_unique<TrafficTrace>(req_.out_dir, req_.trace_background));
  }
  [[nodiscard]] const LaneMap& measured_lanes() const override { return *sumo_lanes_; }
  [[nodiscard]] const ObservedRun& observed() const override { return *observed_; }

  std::vector<sim::Command> start(RunResult& /*result*/, RunLog& log) override {
    auto commands = actors_->place(runtime_->entities());
    add_signal_commands(commands, log);
    add_traffic_commands(commands, {}, log);
    watch_ego(nullptr);
    return commands;
  }
  [[nodiscard]] const std::vector<sim::TrackedActor>& tracked() const override { return actors_->tracked(); }
  std::optional<reference_driver::ReferenceEgo> take_reference_ego() override {
    return std::exchange(reference_ego_, std::nullopt);
  }

  double take_step(const sim::WorldSnapshot& snap, RunResult& result, RunLog& log) override;
  std::optional<CollisionFact> ego_collision(const sim::WorldSnapshot& snap, double time, RunLog& log) override {
    auto fact = sumo_ego_collision(snap, *actors_, ego_, time);
    if (fact) {
      collision_ = fmt::format("the ego {} collided with {} at t={:.2f} s", ego_, fact->with, time);
      log.at(time, *collision_);
    }
    return fact;
  }
  [[nodiscard]] bool ended() const override { return runtime_->finished(); }
  [[nodiscard]] std::string max_time_reason(double max_time) const override {
    return fmt::format("--max-time {} s reached before the Storyboard's StopTrigger", max_time);
  }
  // The storyboard advances a step; the poses of its time t reach SUMO in the next step.
  std::vector<sim::Command> commands(const sim::WorldSnapshot& snap, RunLog& log) override {
    runtime_->step(req_.step);
    auto commands = actors_->place(runtime_->entities());
    add_signal_commands(commands, log);
    add_traffic_commands(commands, snap.traffic, log, snap.nearby);
    watch_ego(&snap);
    return commands;
  }
  [[nodiscard]] bool reached(const std::string& event) const override {
    if (!runtime_) return false;
    const auto& l = runtime_->log();
    return std::any_of(l.begin(), l.end(), [&](const auto& e) { return e.name == event && e.transition == "startTransition"; });
  }
  void conclude(RunResult& result, RunLog& log) override {
    if (runtime_->finished()) {
      result.verdict = Verdict::Success;
      result.reason = fmt::format("the Storyboard's StopTrigger fired at t={:.2f} s", result.sim_time);
      log.at(result.sim_time, result.reason);
    }
    if (!result.traffic.empty() && result.traffic != "none")
      log.note(fmt::format("{} background vehicles in SUMO at the end", background_));
    if (traffic_)
      for (const openscenario::Traffic& t : runtime_->traffic().all()) log.note(traffic_outcome(traffic_record(t, *traffic_)));
    for (const auto& [name, value] : runtime_->monitors()) log.note(fmt::format("monitor {} = {} at the end", name, value));
  }

  void finish(RunResult& result) override {
    if (ego_watch_) {
      result.ego_min_gap = ego_watch_->exposure().min_gap;
      result.ego_min_ttc = ego_watch_->exposure().min_ttc;
    }
    if (actors_) result.actors = entity_records(*actors_, ego_summary_);
    if (observed_) result.collisions = observed_->contacts();
    if (traffic_ && runtime_)
      for (const openscenario::Traffic& t : runtime_->traffic().all()) result.storyboard_traffic.push_back(traffic_record(t, *traffic_));
    if (runtime_)
      for (const auto& [name, value] : runtime_->monitors()) result.monitors.emplace_back(name, value);
  }
  [[nodiscard]] std::optional<std::string> ego_collision_reason() const override { return collision_; }

 private:
  // The reference driver takes the ego (and the ego's watch starts) once the storyboard has
  // placed it; the watch measures every step after.
  void watch_ego(const sim::WorldSnapshot* snap) {
    if (!ego_watch_ && !ego_.empty()) {
      const auto it = runtime_->entities().find(ego_);
      // On no road (a scenario without one) there is no lane ahead to watch.
      if (it != runtime_->entities().end() && it->second.placed && !it->second.road_id.empty()) {
        reference_ego_ = reference_ego_for(ego_model_, *scenario_, *roads_, ego_, it->second, req_.step);
        model_drives_ego_ = reference_ego_.has_value();
        ego_watch_.emplace(lane_path(*roads_, it->second), ego_, object_kinds(*scenario_), 150.0);
      }
    }
    if (ego_watch_ && snap) ego_watch_->step(*snap, actors_->tracked());
  }

  // The traffic signals' states on SUMO's traffic lights (openscenario_signals.hpp); a
  // signal netconvert made no traffic light of is said once in run.log.
  void add_signal_commands(std::vector<sim::Command>& commands, RunLog& log) {
    if (!signals_) return;
    for (auto& c : signals_->update(runtime_->signal_states())) commands.push_back(std::move(c));
    for (const std::string& id : signals_->take_unlinked())
      log.at(runtime_->time(), fmt::format("traffic signal {} has a state but no SUMO traffic light (netconvert made "
                                           "none of it): only the storyboard's conditions see it", id));
  }

  // The storyboard's TrafficActions on SUMO (openscenario_traffic.hpp), from the first one
  // that starts; run.log names each traffic as it starts and stops.
  void add_traffic_commands(std::vector<sim::Command>& commands, const std::vector<sim::NearbyVehicle>& seen,
                            RunLog& log, const std::vector<sim::NearbyVehicle>& background = {}) {
    const openscenario::TrafficBook& book = runtime_->traffic();
    if (book.all().empty()) return;
    if (!traffic_) {
      if (!lanes_ || scenario_->road_file.empty())
        throw MapError("TrafficActions need a road: the RoadNetwork has no LogicFile (SUMO's traffic drives on lanes)");
      traffic_.emplace(*lanes_, req_.seed);
    }
    for (const openscenario::Traffic& t : book.all()) {
      const std::string label = traffic_label(t);
      if (logged_traffic_.insert({t.serial, false}).second) log.at(t.started, label + " starts");
      if (t.stopped && logged_traffic_.insert({t.serial, true}).second) log.at(*t.stopped, label + " stopped");
    }
    for (auto& c : traffic_->update(book, runtime_->entities(), seen, runtime_->time(), req_.step, background))
      commands.push_back(std::move(c));
  }
  static std::string traffic_label(const openscenario::Traffic& t) {
    const std::string name = t.name.empty() ? fmt::format("traffic{}", t.serial) : fmt::format("traffic \"{}\"", t.name);
    return std::visit(
        [&](const auto& spec) {
          using T = std::decay_t<decltype(spec)>;
          if constexpr (std::is_same_v<T, openscenario::TrafficSwarmAction>)
            return fmt::format("{}: TrafficSwarmAction around {}, up to {} vehicles (SUMO vehicles traffic{}.N)", name,
                               spec.entity, spec.vehicles, t.serial);
          else if constexpr (std::is_same_v<T, openscenario::TrafficSourceAction>)
            return fmt::format("{}: TrafficSourceAction, {} vehicles/s within {} m (SUMO vehicles traffic{}.N)", name,
                               spec.rate, spec.radius, t.serial);
          else if constexpr (std::is_same_v<T, openscenario::TrafficAreaAction>)
            return fmt::format("{}: TrafficAreaAction, {} vehicles in {}{} (SUMO vehicles traffic{}.N)", name,
                               spec.entities,
                               spec.polygon.empty() ? fmt::format("{} road range(s)", spec.road_ranges.size())
                                                    : fmt::format("a polygon of {} corners", spec.polygon.size()),
                               spec.continuous ? ", continuous" : "", t.serial);
          else
            return fmt::format("{}: TrafficSinkAction within {} m", name, spec.radius);
        },
        t.spec);
  }

  // An ego that followed the storyboard is handed to SUMO's driver when its (not system under
  // test) controller is activated, like any entity (openscenario_world.hpp): run.log and the
  // report say so, once.
  void note_ego_hand_over(double t, RunLog& log) {
    if (ego_driven_ || ego_handed_ || ego_.empty() || !actors_->is_sumo_driven(ego_)) return;
    ego_handed_ = true;
    const std::string& controller = runtime_->entities().at(ego_).controller;
    const std::string what = fmt::format("SUMO's driver drives it from t={:.2f} s (its controller {} was activated; "
                                         "SUMO stands in for it)", t, controller);
    log.at(t, fmt::format("{}: {}", ego_, what));
    ego_summary_ += "; " + what;
  }

  // --controllers off: an entity's controller activated (or another one activated later) is
  // said once in run.log; it changes nothing.
  void note_controllers_off(double t, RunLog& log) {
    if (actors_->controllers_enabled()) return;
    for (const auto& [name, state] : runtime_->entities()) {
      const std::string active = state.controller_active ? state.controller : "";
      auto& noted = controllers_noted_[name];
      if (active == noted) continue;
      if (!active.empty())
        log.at(t, fmt::format("{}: its controller {} was activated; --controllers off: it goes on following the "
                              "storyboard", name, active));
      noted = active;
    }
  }

  const RunRequest& req_;
  // Declared in this order: the runtime and the actors refer to the roads and lanes.
  std::optional<openscenario::Scenario> scenario_;
  std::optional<opendrive::RoadNetwork> roads_;
  std::optional<opendrive::RoadNetwork> parking_roads_;  // SUMO's road when the scenario has none
  std::optional<opendrive::SumoLaneIndex> lanes_;
  std::optional<openscenario::StoryboardRuntime> runtime_;
  std::optional<OpenScenarioActors> actors_;
  std::optional<OpenScenarioSignals> signals_;  // the storyboard's signals on SUMO's lights (a road only)
  std::optional<OpenScenarioTraffic> traffic_;  // TrafficActions' vehicles (from the first traffic started)
  std::set<std::pair<int, bool>> logged_traffic_;  // (serial, stopped) already in run.log
  std::optional<LaneMap> sumo_lanes_;        // the converted net's lanes, for lane keeping
  std::optional<OpenScenarioRun> observed_;  // the run as metrics and criteria see it
  std::optional<std::string> collision_;     // the ego's first collision, as the verdict says it
  std::optional<reference_driver::ReferenceEgo> reference_ego_;  // --ego-model r157, until the loop takes it
  bool model_drives_ego_ = false;                                // the reference driver drives the ego
  std::optional<reference_driver::EgoWatch> ego_watch_;          // the ego's minimum gap and TTC
  EgoModelChoice ego_model_;
  std::string ego_;
  bool ego_driven_ = false;  // SUMO, the reference driver or a plug-in drives the ego (else the storyboard)
  bool ego_handed_ = false;  // a storyboard ego was handed to SUMO's driver by its activated controller
  std::map<std::string, std::string> controllers_noted_;  // --controllers off: the active controller said per entity
  std::string ego_summary_;  // who drives the ego and why, for run.log and the report
  const char* ego_label_ = "sumo";  // the ego's trace `driver` this step
  std::size_t logged_ = 0;          // storyboard transitions already in the log
  int background_ = 0;              // SUMO vehicles that are not entities, at the last step
};

void OpenScenarioFormat::open(RunResult& result, RunLog& log, SimulatorConfig& config) {
  result.scenario = {req_.scenario_file, sha256_of_file(req_.scenario_file)};
  scenario_.emplace(openscenario::load_scenario(req_.scenario_file, {req_.parameter_overrides}));
  for (const auto& d : scenario_->warnings.items()) {  // what the reader accepted with a warning
    result.warnings.push_back(d.format());
    log.note(d.format());
  }
  result.title = std::filesystem::path(req_.scenario_file).stem().string();
  result.description = scenario_->description;
  // No LogicFile (the standard allows a scenario without a road): the storyboard runs on no
  // road, SUMO on a generated parking road (run/roadless_net.hpp).
  const bool roadless = scenario_->road_file.empty();
  std::filesystem::path parking_xodr;
  result.map_id = roadless ? "none" : std::filesystem::path(scenario_->road_file).stem().string();
  roads_.emplace(roadless ? opendrive::RoadNetwork{} : opendrive::read_xodr_file(scenario_->road_file));
  const opendrive::SumoNet net = roadless ? roadless_sumo_net(opendrive::default_net_cache(), parking_xodr)
                                          : opendrive::convert_to_sumo_net(scenario_->road_file, opendrive::default_net_cache());
  result.net = {net.net_file.string(), sha256_of_file(net.net_file)};
  for (const Diagnostic& d : net.warnings) {  // what the SUMO net leaves out of the road
    result.warnings.push_back(d.format());
    log.note(d.format());
  }
  if (roadless) {
    parking_roads_.emplace(opendrive::read_xodr_file(parking_xodr));
    log.note(fmt::format("no road (the RoadNetwork has no LogicFile): entities move by world positions; SUMO net {} "
                         "(a generated parking road far from the scene, where entities enter SUMO)",
                         net.net_file.string()));
  } else {
    log.note(fmt::format("road {} -> SUMO net {} ({})", scenario_->road_file, net.net_file.string(),
                         net.from_cache ? "cached" : "converted now"));
  }
  const Diagnostics truncated = truncate_synchronize_targets(*scenario_, *roads_);  // as the peer does, said
  for (const auto& d : truncated.items()) {
    result.warnings.push_back(d.format());
    log.note(d.format());
  }
  lanes_.emplace(roadless ? *parking_roads_ : *roads_, net.net_file.string());
  if (!roadless) signals_.emplace(opendrive::read_sumo_signal_links(net.net_file.string()));
  const EgoChoice chosen = choose_ego(*scenario_, req_.ego_entity);
  ego_ = chosen.entity;
  check_external_ego(*scenario_, ego_, req_.ego_link != nullptr);
  ego_model_ = ego_model_of(req_, *scenario_, ego_);
  if (req_.ego_link && ego_model_.own_model())
    throw OrchError("--ego-port: an external ego drives the ego; the orchestrator's own model (--ego-model " +
                    ego_model_.name + " or an R157ReferenceDriver controller) cannot drive it too");
  if (req_.controllers_off) check_controllers_off(req_);
  const EgoDriving driving = ego_driving(chosen, {req_.ego_model_given ? req_.ego_model.name : "",
                                                  req_.ego_model.r157(), req_.ego_link != nullptr,
                                                  req_.controllers_off});
  ego_driven_ = driving.driven;
  if (!ego_driven_) ego_model_ = EgoModelChoice{};  // nothing drives it: no reference driver either
  // A file without an ego (no system-under-test controller, no name rule, no --ego): "none",
  // not the default model's name (the report's header said "ego driven by sumo").
  result.ego_model = ego_.empty() ? "none" : ego_driven_ ? ego_model_.name : "storyboard";
  result.controllers = req_.controllers_off ? "off" : "on";
  if (req_.controllers_off)
    log.note("--controllers off: no controller runs, every entity follows the storyboard (the file's controllers are "
             "read and checked; Activate/AssignControllerActions run and are logged, and hand nobody to SUMO)");
  ego_summary_ = ego_.empty() ? ""
                 : !ego_driven_ ? fmt::format("follows the storyboard ({})", driving.why)
                 : req_.ego_link ? fmt::format("driven by SUMO's car-following model until an ActivateControllerAction "
                                               "hands it to the external ego ({})", driving.why)
                                 : fmt::format("driven by {} ({})",
                                               ego_model_.r157()     ? "the UN R157 reference driver"
                                               : ego_model_.cruise() ? "the cruise model (its set speed, no braking)"
                                                                     : "SUMO",
                                               driving.why);
  log.note(ego_.empty() ? fmt::format("no ego: {}", chosen.rule)
                        : fmt::format("{}: {}; the ego of metrics and the report because {}{}", ego_, ego_summary_,
                                      chosen.rule, req_.ego_link ? " (SUMO vehicle \"ego\")" : ""));
  if (req_.evaluation) check_criteria(*req_.evaluation, *scenario_, ego_, log);
  runtime_.emplace(*scenario_, *roads_, static_cast<std::uint64_t>(req_.seed));
  actors_.emplace(*scenario_, *lanes_, ego_,
                  !ego_driven_ ? EgoDrive::Storyboard : req_.ego_link ? EgoDrive::External : EgoDrive::Sumo);
  if (req_.controllers_off) actors_->disable_controllers();
  sumo_lanes_.emplace(LaneMap::build(net.net_file.string(), WaypointFile{}));
  observed_.emplace(*scenario_, *roads_, *actors_);

  config.net_file = std::filesystem::absolute(net.net_file).string();
  if (const auto traffic = traffic_route_file(req_, net.net_file, result, log); !traffic.empty())
    config.route_files.push_back(traffic);
  if (req_.ssm && !ego_.empty() && ego_driven_) {  // the ego is SUMO's (its vehicle id is the entity's name)
    const auto ssm = ssm_device_arguments(ego_, req_.out_dir / kSsmFileName);
    config.extra_args.insert(config.extra_args.end(), ssm.begin(), ssm.end());
  }
}

double OpenScenarioFormat::take_step(const sim::WorldSnapshot& snap, RunResult& result, RunLog& log) {
  // The poses of storyboard time t reached SUMO in this step: the step's time is t.
  const double t = runtime_->time();
  background_ = snap.other_vehicles;
  const auto ego_driver = ego_.empty() ? OpenScenarioEgo::Driver::Sumo
                         : !ego_driven_ ? OpenScenarioEgo::Driver::Storyboard
                                        : actors_->ego_drive().driver(runtime_->entities().at(ego_));
  const bool model_drives = model_drives_ego_ && ego_driver == OpenScenarioEgo::Driver::Sumo;
  ego_label_ = model_drives ? ego_model_.name.c_str()
               : !ego_driven_ && !ego_.empty() && actors_->is_sumo_driven(ego_) ? "sumo"  // an activated controller
                                                                               : OpenScenarioEgo::label(ego_driver);
  note_ego_hand_over(t, log);
  note_controllers_off(t, log);
  observed_->update(snap, t, runtime_->entities(), runtime_->finished());
  // Entities SUMO (or the external ego) drove are what the storyboard's conditions see of
  // them from now on; while the storyboard moves the ego laterally, its own state stands.
  // (The observers see the step afterwards, through observed_, which does not read the runtime.)
  for (const std::string& driven : actors_->sumo_driven()) {
    if (driven == ego_ && ego_driven_ && ego_driver == OpenScenarioEgo::Driver::Storyboard) continue;
    if (const sim::ActorState* e = find_actor(snap, *actors_, driven); e && e->present) {
      const Vec2 ref = actors_->reference_point(*e);
      runtime_->observe(driven, {ref.x(), ref.y(), e->heading}, e->speed, e->accel);
    }
  }
  for (const auto& l = runtime_->log(); logged_ < l.size(); ++logged_) {
    result.events.push_back(storyboard_event(l[logged_]));
    log.at(l[logged_].time, result.events.back().text);
  }
  return t;
}

}  // namespace

std::unique_ptr<RunFormat> openscenario_format(const RunRequest& request) {
  return std::make_unique<OpenScenarioFormat>(request);
}

}  // namespace orch
