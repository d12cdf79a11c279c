#pragma once
// The scenario interpreter. Each step it reads a WorldSnapshot and returns Commands:
//   conditions -> scene transitions -> actions -> scripted actors' next poses.
// It never calls SUMO (ARCHITECTURE.md "One step, as data"), so every rule here is unit
// testable with hand-made snapshots.
//
// Timing: step(snapshot at t) moves the scripted actors to their poses for t + dt, which
// the simulator shows after its next step. start() places them at their poses for the
// first step, when SUMO inserts every actor.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "scenario_executor_engine/actor_table.hpp"
#include "scenario_executor_engine/collision.hpp"
#include "scenario_executor_engine/lane_change_conflicts.hpp"
#include "scenario_executor_engine/motion.hpp"
#include "scenario_executor_engine/route_crossing.hpp"
#include "scenario_executor_engine/scene_machine.hpp"
#include "scenario_executor_engine/sim_names.hpp"
#include "map/lane_map.hpp"
#include "map/waypoint_file.hpp"
#include "scenario_executor/model.hpp"

namespace orch::engine {

struct MapContext {
  const WaypointFile& waypoints;
  const LaneMap& lanes;
  double lane_extension = 20.0;  // m the lanes reach beyond the routes' ends
};

struct EngineOptions {
  double step = 0.05;  // s
  // An external plug-in drives the ego (run --ego-port): the engine does not drive it. No
  // route speed, no stop at end_position (the scenario still judges them), and the ego's
  // vehicle type keeps its own top speed, so a plug-in commanding 100 km/h on a 60 km/h
  // route gets 100 km/h. Everything else (insertion, start pose, hand_over) is as usual.
  bool external_ego = false;
};

// Storyboard: an OpenSCENARIO storyboard element's transition (Storyboard, Story, Act,
// ManeuverGroup, Maneuver, Event; their actions are Action).
enum class EventKind { Scene, Action, Info, Warning, Storyboard };

// One entry of the run's account. Besides its text, the structured fields say what it is
// about, so that tools need not parse the text: the actor an action or warning concerns,
// and the scene the scenario was in when it happened.
struct Event {
  Event() = default;
  Event(double t, EventKind k, std::string words, std::optional<ActorId> about = std::nullopt)
      : time(t), kind(k), text(std::move(words)), actor(about) {}

  double time = 0;
  EventKind kind = EventKind::Info;
  std::string text;
  std::optional<ActorId> actor;  // the actor it concerns, if one
  std::optional<int> scene;      // the scene after this step's transition (set by Engine::step)
};

enum class RunState { Running, EndingReached, StopConditionMet, Error };

struct StepOutput {
  std::vector<Command> commands;
  std::vector<Event> events;
};

// What a hand_over action asked for, kept for an external ego plug-in and the results.
struct HandOverRecord {
  double time = 0;
  scenario::HandOverAction action;
};

class Engine {
 public:
  Engine(const scenario::Scenario& s, MapContext map, const Catalog& catalog, EngineOptions options);

  // Spawns every actor; must be called once before the first step.
  StepOutput start();
  StepOutput step(const WorldSnapshot& snapshot);

  [[nodiscard]] std::vector<TrackedActor> tracked() const { return actors_.tracked(); }
  [[nodiscard]] const ActorTable& actors() const { return actors_; }
  [[nodiscard]] scenario::SceneId scene() const { return machine_.current(); }
  [[nodiscard]] const std::vector<SceneVisit>& visits() const { return machine_.visits(); }
  [[nodiscard]] RunState state() const { return state_; }
  [[nodiscard]] const std::string& end_reason() const { return end_reason_; }
  // The last snapshot as the engine judged it: scripted actors carry their commanded speed
  // and acceleration (SUMO only sees the poses).
  [[nodiscard]] const WorldSnapshot& judged() const { return current_; }
  [[nodiscard]] bool siren(ActorId id) const;
  [[nodiscard]] bool scripted(ActorId id) const { return motions_.count(id) > 0; }
  [[nodiscard]] const std::vector<HandOverRecord>& hand_overs() const { return hand_overs_; }
  // Every contact so far (own geometry test and SUMO's reports), in the order they began.
  [[nodiscard]] const std::vector<Contact>& contacts() const { return collisions_.all(); }
  // Background vehicles that were in the way of a scripted lane change.
  [[nodiscard]] const std::vector<LaneChangeConflict>& lane_change_conflicts() const { return conflicts_.all(); }
  // "actor 1", "actor 0 (ego)" or "vehicle <SUMO id>" for a contact's body name.
  [[nodiscard]] std::string describe_body(const std::string& name) const;
  // The actor a contact's body name ("3") names; nullopt for a background vehicle.
  [[nodiscard]] std::optional<ActorId> actor_named(const std::string& name) const;
  // The route an actor drives now (the reference line of along-road measures), or null.
  [[nodiscard]] const WaypointRoute* route_of(ActorId id) const;

 private:
  // Longitudinal behaviour of a scripted actor (the latest action on that axis wins).
  struct HoldSpeed {
    scenario::SpeedAction action;
  };
  struct KeepGap {
    scenario::TraveledDistanceAction action;
  };
  struct KeepSpeed {};  // after a route_move: go on at the speed the last leg ended with
  using Longitudinal = std::variant<HoldSpeed, KeepGap, KeepSpeed>;

  void place_opening_actors(StepOutput& out);
  void place_other(const scenario::OtherOpening& o);
  void spawn_ego(StepOutput& out);
  [[nodiscard]] double ego_start_s() const;

  void enter_scene(const scenario::Scene& scene, double t, StepOutput& out);
  void start_action(const scenario::Action& a, double t, StepOutput& out);
  void start_route_move(const scenario::RouteMoveAction& a, ScriptedMotion& m, double t, StepOutput& out);
  void move_scripted_actors(double t, StepOutput& out);
  void resolve_longitudinal(ActorId id, ScriptedMotion& m);
  void update_ego(StepOutput& out);
  void check_placement(const ActorState& a, double t, StepOutput& out);
  [[nodiscard]] SetPose pose_command(const ActorSlot& slot, const ScriptedMotion& m) const;
  StepOutput step_scene_graph(const WorldSnapshot& snapshot);
  [[nodiscard]] bool collided(ActorId id) const;

  void fail(const std::string& reason, double t, StepOutput& out);

  const scenario::Scenario& scenario_;
  MapContext map_;
  EngineOptions options_;
  ActorTable actors_;
  SceneMachine machine_;
  CollisionMonitor collisions_;
  LaneChangeConflicts conflicts_;

  std::map<ActorId, ScriptedMotion> motions_;
  std::map<ActorId, Longitudinal> longitudinal_;
  std::map<ActorId, int> signals_;
  std::map<ActorId, bool> sirens_;
  std::vector<HandOverRecord> hand_overs_;

  const WaypointRoute* ego_route_ = nullptr;
  double ego_s_ = 0;
  double ego_max_speed_ = 0;
  bool ego_stop_sent_ = false;

  WorldSnapshot current_;
  std::optional<WorldSnapshot> previous_;
  RunState state_ = RunState::Running;
  std::string end_reason_;
  std::map<ActorId, bool> reported_route_end_;
  std::map<ActorId, std::pair<std::string, int>> placed_on_;  // lane of the last pose, when centred on it
  std::set<std::string> misplaced_;                            // placements already reported
  RouteMeetings meetings_;                                     // where routes without a common path meet
  static constexpr double kCentredOnLane = 0.5;                // m from the lane centre
};

}  // namespace orch::engine
