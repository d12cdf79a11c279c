#pragma once
// A loaded ScenarioExecutor scenario as immutable plain values. Every block, condition and
// action of the format is here; the loader checks every reference before a run starts, so
// the engine never meets a dangling actor id, scene id or waypoint.
//
// Units are converted at load time: speeds in m/s (the file says km/h), distances in m,
// times in s, accelerations in m/s^2, angles in rad.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/diagnostics.hpp"
#include "map/position.hpp"
#include "sim/actor.hpp"

namespace orch::scenario {

using sim::ActorId;  // the simulator's actor ids are the format's
using SceneId = int;

// Scene id of the opening scene in logs, traces and results (the format gives it none).
inline constexpr SceneId kOpeningSceneId = 0;

enum class Comparison { Greater, GreaterEqual, Equal, LessEqual, Less };
enum class SpeedType { Absolute, Relative };
enum class AccelType { Specify, GodsHand };  // file: "specify" | "gods_hand" | "god_hands"
enum class MeasureType { Center, Surface };
enum class DistanceType { Traveled, Straight };
enum class RouteMoveType { Waypoint, WpOffset };
enum class StartPositionType { Waypoint, Distance };
enum class Logic { And, Or };

// A point of a RoadEditor route (wp_id, wp_idx, where): one alternative of the positions
// both languages share, resolved in map/ (map/position_resolver.hpp).
using position::WaypointRef;

struct Accel {
  AccelType type = AccelType::GodsHand;  // absent "accel" = instant, as in the reference
  double value = 0;                      // m/s^2, magnitude; used for speeding up and slowing down
};

// ---------------------------------------------------------------- conditions
struct PositionCondition {  // type "reach"
  ActorId actor = 0;
  WaypointRef waypoint;
  double tolerance = 0;  // m, radius around the waypoint
};
struct DistanceCondition {
  ActorId actor = 0;
  ActorId target = 0;
  DistanceType type = DistanceType::Traveled;
  Comparison comparison = Comparison::Less;
  double value = 0;  // m; + = target ahead of actor
  MeasureType measure = MeasureType::Center;
};
struct SpeedCondition {
  ActorId actor = 0;
  SpeedType type = SpeedType::Absolute;
  std::optional<ActorId> target;  // for relative
  Comparison comparison = Comparison::GreaterEqual;
  double value = 0;  // m/s (relative: actor minus target)
};
struct TimeHeadwayCondition {
  ActorId actor = 0;
  WaypointRef waypoint;
  Comparison comparison = Comparison::LessEqual;
  double value = 0;  // s
};
struct CollisionCondition {
  ActorId actor = 0;
  // Real files write it (the reference implementation ignores every key of "collision"):
  // then only a contact of `actor` with this actor counts.
  std::optional<ActorId> target;
};
struct SimulationTimeCondition {
  Comparison comparison = Comparison::GreaterEqual;
  double value = 0;  // s
};

using ConditionKind = std::variant<PositionCondition, DistanceCondition, SpeedCondition,
                                   TimeHeadwayCondition, CollisionCondition, SimulationTimeCondition>;

struct Condition {
  ConditionKind kind;
  std::string description;
  SourceLocation where;
};

struct ConditionItem;
// {"and": [...]} or {"or": [...]}. An empty group is always true (a scene without
// conditions is entered as soon as it may be). Items may themselves be groups.
struct ConditionGroup {
  Logic logic = Logic::And;
  std::vector<ConditionItem> items;
  SourceLocation where;
};
struct ConditionItem {
  std::variant<Condition, ConditionGroup> node;
};

// ---------------------------------------------------------------- actions
struct SpeedAction {
  ActorId actor = 0;
  SpeedType type = SpeedType::Absolute;
  std::optional<ActorId> target;  // relative: speed = target's speed + value, every step
  double value = 0;               // m/s
  Accel accel;
};
struct TraveledDistanceAction {
  ActorId actor = 0;
  ActorId target = 0;
  double value = 0;  // m along the road; + = actor ahead of target
  MeasureType measure = MeasureType::Center;
};
struct LaneChangeAction {
  ActorId actor = 0;
  std::string wp_id;  // route whose lane the actor moves onto
  double time = 0;    // s for the lateral move
};
struct LaneOffsetAction {
  ActorId actor = 0;
  double value = 0;  // m from the lane centre, + = left
  double time = 0;   // s
};
struct RouteLeg {
  double time = 0;                  // s from the previous point to this one
  std::optional<WaypointRef> waypoint;  // type waypoint
  std::optional<double> wp_offset;      // m, + = left
  SourceLocation where;
};
struct RouteMoveAction {
  ActorId actor = 0;
  RouteMoveType type = RouteMoveType::Waypoint;
  std::vector<RouteLeg> legs;
};
struct LightStateAction {  // an absent key leaves that light as it is
  ActorId actor = 0;
  std::optional<bool> blinker_left;
  std::optional<bool> blinker_right;
  std::optional<bool> special1;
};
struct SoundStateAction {
  ActorId actor = 0;
  std::optional<bool> sound;
};
struct HandOverAction {  // for an external ego stack: take over (true) or give back control
  std::optional<ActorId> actor;
  bool hand_over = false;
  std::optional<double> throttle;
  std::optional<double> brake;
  std::optional<double> steer;
};
// `{}` in an action list (real files have it): does nothing.
struct EmptyAction {};

using ActionKind = std::variant<SpeedAction, TraveledDistanceAction, LaneChangeAction, LaneOffsetAction,
                                RouteMoveAction, LightStateAction, SoundStateAction, HandOverAction,
                                EmptyAction>;

struct Action {
  ActionKind kind;
  std::string description;
  SourceLocation where;
};

// ---------------------------------------------------------------- actors and scenes
struct ActorSpec {
  ActorId id = 0;
  std::string model_id;
  std::string color;  // "rrggbb", "" = not given
  std::string description;
  bool is_ego = false;
  SourceLocation where;
};

struct StartPosition {
  StartPositionType type = StartPositionType::Waypoint;
  std::optional<WaypointRef> waypoint;  // type waypoint
  double wp_offset = 0;                 // m, + = left of the route
  std::optional<double> heading;        // rad, relative to the route direction, + = to the left
  std::optional<ActorId> target;        // type distance
  double distance = 0;                  // m along the road from the target, + = ahead of it
  MeasureType measure = MeasureType::Center;
  SourceLocation where;
  // Where it is, as one of the shared positions: a WaypointRef, or a RouteDistance from the
  // target actor (named by its id in decimal). wp_offset and heading apply on top.
  // `ego`: the target when none is named (the loader names one always).
  [[nodiscard]] position::Position position(ActorId ego) const;
};

struct EgoOpening {
  StartPosition start;                // always type waypoint
  std::optional<WaypointRef> end;     // the ego drives to here and stops
};

struct OtherOpening {
  ActorId actor = 0;
  std::string description;
  StartPosition start;
  std::optional<SpeedAction> start_speed;  // applied at t=0 like a speed action
  SourceLocation where;
};

struct OpeningScene {
  EgoOpening ego;
  std::vector<OtherOpening> others;
  std::vector<SceneId> next_scenes;
  SourceLocation where;
};

struct Scene {
  SceneId id = 0;
  std::string description;
  double duration = 0;  // s the scene is held before its next_scenes are tried
  ConditionGroup conditions;
  std::vector<Action> actions;
  std::vector<SceneId> next_scenes;
  bool ending = false;
  SourceLocation where;
};

struct Scenario {
  std::string file;
  std::string title;
  std::string description;
  std::string map_id;
  // "traffic" (an extension of the format): the scenario's own background traffic, a SUMO
  // route file relative to the scenario file, or a level as `run --traffic` takes it;
  // `run --traffic` overrides it (docs/background-traffic.md).
  std::string traffic;
  ActorSpec ego;
  std::vector<ActorSpec> others;
  OpeningScene opening;
  std::vector<Scene> scenes;  // intermediate and ending scenes, in file order
  std::optional<ConditionGroup> stop_conditions;

  [[nodiscard]] const Scene* find_scene(SceneId id) const {
    for (const auto& s : scenes)
      if (s.id == id) return &s;
    return nullptr;
  }
  [[nodiscard]] const ActorSpec* find_actor(ActorId id) const {
    if (ego.id == id) return &ego;
    for (const auto& a : others)
      if (a.id == id) return &a;
    return nullptr;
  }
};

// Text of a comparison as written in files and logs (">=", ...).
const char* to_string(Comparison c);
inline bool compare(double lhs, Comparison c, double rhs) {
  switch (c) {
    case Comparison::Greater: return lhs > rhs;
    case Comparison::GreaterEqual: return lhs >= rhs;
    case Comparison::Equal: return lhs == rhs;
    case Comparison::LessEqual: return lhs <= rhs;
    case Comparison::Less: return lhs < rhs;
  }
  return false;
}

}  // namespace orch::scenario
