#pragma once
// A loaded OpenSCENARIO 1.x scenario as plain immutable values: parameters already
// substituted, catalog references resolved, every entity reference checked. The storyboard
// runtime (element states, edges, timers) lives apart from these values.
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "core/diagnostics.hpp"
#include "map/position.hpp"
#include "openscenario/traffic_model.hpp"
#include "openscenario/trajectory_model.hpp"

namespace orch::openscenario {

struct Place {  // where an element came from, for runtime messages
  std::string path;
  int line = 0;
};

struct Parameter {
  std::string name;
  std::string type;   // integer, double, string, unsignedInt, unsignedShort, boolean, dateTime
  std::string value;  // after --param overrides
  bool overridden = false;
};

// ---- Entities -----------------------------------------------------------------------
struct BoundingBox {
  double center_x = 0, center_y = 0, center_z = 0;  // relative to the reference point
  double width = 0, length = 0, height = 0;
};
struct Performance {
  double max_speed = 0, max_acceleration = 0, max_deceleration = 0;
};
struct Axle {
  double max_steering = 0, wheel_diameter = 0, track_width = 0, position_x = 0, position_z = 0;
};
struct Controller {
  std::string name;
  std::map<std::string, std::string> properties;
};
enum class EntityKind { Vehicle, Pedestrian, MiscObject };
struct Entity {
  std::string name;
  EntityKind kind = EntityKind::Vehicle;
  std::string object_name;  // the Vehicle / Pedestrian / MiscObject's own name (catalog entry)
  std::string category;     // vehicleCategory, pedestrianCategory or miscObjectCategory
  BoundingBox box;
  std::optional<Performance> performance;  // vehicles
  std::optional<Axle> front_axle, rear_axle;
  double mass = 0;
  std::map<std::string, std::string> properties;
  std::optional<Controller> controller;  // the default one: the first ObjectController
  // 1.3: every ObjectController by its name (an unnamed one has ""); ActivateControllerAction's
  // objectControllerRef chooses among them. Empty when the entity has none.
  std::vector<std::pair<std::string, Controller>> object_controllers;
  // Trailers (1.3): where a trailer couples on this vehicle (hitch) and where this vehicle,
  // as a trailer, couples on its tractor (coupler), as x offsets from the reference point;
  // `trailer` names the entity connected at the start ("" none).
  std::optional<double> trailer_hitch_dx, trailer_coupler_dx;
  std::string trailer;
};

// ---- Positions ----------------------------------------------------------------------
// One variant for both languages, resolved in map/ (map/position_resolver.hpp); the reader
// produces the seven OpenSCENARIO kinds.
using position::LanePosition;
using position::Orientation;
using position::Position;
using position::RelativeLanePosition;
using position::RelativeObjectPosition;
using position::RelativeRoadPosition;
using position::RelativeWorldPosition;
using position::InRouteFromEntity;
using position::InRouteFromLane;
using position::InRouteFromRoad;
using position::RoadPosition;
using position::RoutePosition;
using position::TrajectoryPosition;
using position::GeoPosition;
using position::WorldPosition;

// ---- Actions ------------------------------------------------------------------------
enum class DynamicsShape { Step, Linear, Cubic, Sinusoidal };
enum class DynamicsDimension { Time, Distance, Rate };
struct TransitionDynamics {
  DynamicsShape shape = DynamicsShape::Step;
  DynamicsDimension dimension = DynamicsDimension::Time;
  double value = 0;
};
struct TeleportAction { Position position; };
struct AbsoluteTargetSpeed { double value = 0; };
struct RelativeTargetSpeed {
  std::string entity;
  double value = 0;
  bool factor = false;  // speedTargetValueType: delta (false) or factor (true)
  bool continuous = false;
};
struct SpeedAction {
  TransitionDynamics dynamics;
  std::variant<AbsoluteTargetSpeed, RelativeTargetSpeed> target;
};
struct LaneChangeAction {
  TransitionDynamics dynamics;
  std::optional<double> target_lane_offset;
  // Relative: lanes counted from `entity`'s lane (positive = left); absolute: a lane id.
  std::optional<std::string> relative_to;
  int lane = 0;
};
struct LaneOffsetAction {
  bool continuous = false;
  DynamicsShape shape = DynamicsShape::Step;
  std::optional<double> max_lateral_acc;
  std::optional<std::string> relative_to;  // RelativeTargetLaneOffset entity, else absolute
  double value = 0;
};
struct LongitudinalDistanceAction {
  std::string entity;
  std::optional<double> distance;
  std::optional<double> time_gap;
  bool freespace = false;
  bool continuous = false;
  std::string coordinate_system = "entity";
  std::string displacement = "trailingReferencedEntity";
  std::optional<double> max_acceleration, max_deceleration, max_speed;
  // DynamicConstraints' jerk limits (m/s^3): how fast the acceleration may grow (and the
  // deceleration shrink), and how fast it may fall (the deceleration grow).
  std::optional<double> max_acceleration_rate, max_deceleration_rate;
};
// SpeedProfileAction (1.2): the speeds to reach one after the other, each in its entry's time
// (from the entry before; absent: as fast as the DynamicConstraints allow). With an entity
// the speeds are relative to its speed when the action starts. followingMode "position": the
// speed changes linearly along the profile; "follow": it tracks the profile within the
// constraints (acceleration, deceleration and their rates, maxSpeed).
struct SpeedProfileEntry {
  std::optional<double> time;
  double speed = 0;
};
struct SpeedProfileAction {
  std::optional<std::string> relative_to;  // entityRef
  bool follow = false;
  std::optional<double> max_acceleration, max_deceleration, max_acceleration_rate, max_deceleration_rate, max_speed;
  std::vector<SpeedProfileEntry> entries;
};
struct ActivateControllerAction {
  std::optional<bool> lateral, longitudinal;
  std::string object_controller;  // objectControllerRef (1.3; controllerRef deprecated): "" the current one
};
// Replaces the entity's controller; 1.2's activateLateral / activateLongitudinal activate it.
struct AssignControllerAction {
  Controller controller;
  std::optional<bool> lateral, longitudinal;
};
struct VisibilityAction { bool graphics = true, traffic = true, sensors = true; };
// TimeReference/Timing: trajectory time = (simulation time, or time since the action
// started when relative) ; a vertex is due at vertex time * scale + offset.
struct TrajectoryTiming {
  bool absolute = true;
  double scale = 1, offset = 0;
};
struct FollowTrajectoryAction {
  Trajectory trajectory;
  std::optional<TrajectoryTiming> timing;  // None: the entity keeps its own speed along the path
  bool follow_mode = false;               // followingMode "follow" (else "position")
  double initial_distance_offset = 0;
};
// Routes: waypoints mapped onto the road network when the action starts.
struct AssignRouteAction {
  std::string name;
  bool closed = false;
  std::vector<Position> waypoints;
  std::vector<std::string> strategies;  // each Waypoint's routeStrategy (the leg leading to it)
  std::vector<Place> waypoint_places;   // each Waypoint's element, for runtime messages
};
struct AcquirePositionAction { Position position; };
// Global actions (no actors).
struct AddEntityAction { std::string entity; Position position; };
struct DeleteEntityAction { std::string entity; };
struct ParameterSetAction { std::string parameter; std::string value; };
struct ParameterModifyAction {
  std::string parameter;
  bool multiply = false;  // ParameterMultiplyByValueRule, else ParameterAddValueRule
  double value = 0;
};
// Variables (1.2): declared like parameters, but only actions and conditions use them.
struct VariableSetAction { std::string variable; std::string value; };
struct VariableModifyAction {
  std::string variable;
  bool multiply = false;  // VariableMultiplyByValueRule, else VariableAddValueRule
  double value = 0;
};
// Actions read and run as instant ones with no effect on any entity's motion: a vehicle's
// lights (AppearanceAction / LightStateAction) and the environment (EnvironmentAction:
// time of day, weather, road condition). SUMO runs render neither; `element` names which.
struct AppearanceAction { std::string element; };
// An Environment's TimeOfDay: the time it sets (seconds since 1970-01-01T00:00:00 UTC, see
// openscenario/date_time.hpp) and whether it then runs on with the simulation time.
struct TimeOfDaySetting {
  double date_time = 0;
  bool animation = false;
};
struct EnvironmentAction {
  std::string name;
  std::optional<TimeOfDaySetting> time_of_day;  // the only part a condition reads
};
// Trailers (1.3): the actor tows `trailer` from now on / no trailer any more.
// SynchronizeAction (openscenario/synchronize.hpp): reach `position` when the master `entity`
// reaches `master_position`; tolerances in m (absent: kSynchronizeTolerance).
struct SynchronizeFinalSpeed {
  bool relative = false;  // RelativeSpeedToMaster (delta or factor), else AbsoluteSpeed
  bool factor = false;
  double value = 0;
  std::optional<double> steady_distance, steady_time;  // TargetDistance/TimeSteadyState
};
struct SynchronizeAction {
  std::string entity;  // masterEntityRef
  Position master_position;
  Position position;
  std::optional<double> tolerance_master, tolerance;
  std::optional<SynchronizeFinalSpeed> final_speed;
};
// Traffic signals (openscenario/traffic_signals.hpp): a signal's state is its lamps as the
// file writes them ("on;off;off"); a controller cycles through its phases.
struct TrafficSignalStateAction { std::string signal; std::string state; };  // name, state
struct TrafficSignalControllerAction { std::string controller; std::string phase; };
// LateralDistanceAction: keep `distance` (absent: the current one) sideways to `entity`,
// measured in the road's t (coordinateSystem road / lane) or the entity's frame; with
// freespace between the bounding boxes. Limits as DynamicConstraints (absent: at once).
struct LateralDistanceAction {
  std::string entity;
  std::optional<double> distance;
  bool freespace = false;
  bool continuous = false;
  std::string coordinate_system = "entity";
  std::string displacement = "any";  // any, leftToReferencedEntity, rightToReferencedEntity
  std::optional<double> max_acceleration, max_deceleration, max_speed;
};
// SetMonitorAction (1.3): sets the monitor `monitor` (MonitorDeclarations) to `value`.
struct SetMonitorAction {
  std::string monitor;
  bool value = false;
};
struct ConnectTrailerAction { std::string entity; };  // the trailer (checked like every `entity`)
struct DisconnectTrailerAction {};
// RoutingAction/RandomRouteAction (1.3, no content): the entity drives a random route, its own
// choice at every fork, from where it is (openscenario/random_route.hpp).
struct RandomRouteAction {};
using PrivateAction = std::variant<TeleportAction, SpeedAction, SpeedProfileAction, LaneChangeAction, LaneOffsetAction,
                                   LongitudinalDistanceAction, ActivateControllerAction, AssignControllerAction,
                                   VisibilityAction, FollowTrajectoryAction, AssignRouteAction, AcquirePositionAction,
                                   AddEntityAction, DeleteEntityAction, ParameterSetAction, ParameterModifyAction,
                                   VariableSetAction, VariableModifyAction, ConnectTrailerAction,
                                   DisconnectTrailerAction, AppearanceAction, EnvironmentAction, SynchronizeAction,
                                   TrafficSignalStateAction, TrafficSignalControllerAction, LateralDistanceAction,
                                   TrafficSwarmAction, TrafficSourceAction, TrafficSinkAction, TrafficStopAction,
                                   SetMonitorAction, TrafficAreaAction, RandomRouteAction>;
// Which alternatives are global actions (they take no actors).
template <class T>
inline constexpr bool kIsGlobalAction =
    std::is_same_v<T, AddEntityAction> || std::is_same_v<T, DeleteEntityAction> ||
    std::is_same_v<T, ParameterSetAction> || std::is_same_v<T, ParameterModifyAction> ||
    std::is_same_v<T, VariableSetAction> || std::is_same_v<T, VariableModifyAction> ||
    std::is_same_v<T, EnvironmentAction> || std::is_same_v<T, TrafficSignalStateAction> ||
    std::is_same_v<T, TrafficSignalControllerAction> || std::is_same_v<T, TrafficSwarmAction> ||
    std::is_same_v<T, TrafficSourceAction> || std::is_same_v<T, TrafficSinkAction> || std::is_same_v<T, TrafficStopAction> ||
    std::is_same_v<T, SetMonitorAction> || std::is_same_v<T, TrafficAreaAction>;

// ---- Conditions and triggers --------------------------------------------------------
enum class Rule { EqualTo, GreaterThan, LessThan, GreaterOrEqual, LessOrEqual, NotEqualTo };
enum class Edge { None, Rising, Falling, RisingOrFalling };
struct SimulationTimeCondition { Rule rule = Rule::GreaterOrEqual; double value = 0; };
struct StoryboardElementStateCondition {
  std::string type;   // story, act, maneuverGroup, maneuver, event, action
  std::string ref;    // as written: a name, or a path of names "story::act::...::name"
  std::string key;    // the element it resolves to (its `key`), set by the reader
  std::string state;  // startTransition, endTransition, ..., runningState, completeState
};
struct ParameterCondition { std::string parameter; Rule rule = Rule::EqualTo; std::string value; };
struct VariableCondition { std::string variable; Rule rule = Rule::EqualTo; std::string value; };
// A signal's state / a controller's phase now equal the condition's (traffic_signals.hpp).
struct TrafficSignalCondition { std::string signal; std::string state; };
struct TrafficSignalControllerCondition { std::string controller; std::string phase; };
// TimeOfDayCondition: the time of day now (the last EnvironmentAction's TimeOfDay, run on
// since then when it animates) against `date_time` (as TimeOfDaySetting). No time of day set
// yet: false.
struct TimeOfDayCondition {
  Rule rule = Rule::EqualTo;
  double date_time = 0;
};
struct SpeedCondition { Rule rule = Rule::GreaterThan; double value = 0; };
struct RelativeDistanceCondition {
  std::string entity;
  std::string distance_type;      // longitudinal, lateral, cartesianDistance, euclidianDistance
  std::string coordinate_system;  // entity, road, lane
  bool freespace = false;
  Rule rule = Rule::LessThan;
  double value = 0;
};
struct TraveledDistanceCondition { double value = 0; };
struct StandStillCondition { double duration = 0; };
struct EndOfRoadCondition { double duration = 0; };
struct OffroadCondition { double duration = 0; };
struct AccelerationCondition { Rule rule = Rule::GreaterThan; double value = 0; };
struct ReachPositionCondition { Position position; double tolerance = 0; };
struct RelativeSpeedCondition { std::string entity; Rule rule = Rule::GreaterThan; double value = 0; };
struct TimeHeadwayCondition {
  std::string entity;
  bool freespace = false;
  std::string coordinate_system = "entity";
  std::string distance_type = "euclidianDistance";  // the standard's default when not given
  Rule rule = Rule::LessThan;
  double value = 0;
};
struct DistanceCondition {
  Position position;
  std::string distance_type = "euclidianDistance";
  std::string coordinate_system = "entity";
  bool freespace = false;
  Rule rule = Rule::LessThan;
  double value = 0;
};
// Time to collision with an entity or a position (a point at rest): the distance (as in
// RelativeDistanceCondition) divided by the rate at which it shrinks; infinite when it does not.
struct TimeToCollisionCondition {
  std::optional<std::string> entity;  // else `position`
  std::optional<Position> position;
  std::string distance_type = "euclidianDistance";
  std::string coordinate_system = "entity";
  bool freespace = false;
  Rule rule = Rule::LessThan;
  double value = 0;
};
// The bounding boxes overlap: with the entity `entity`, or with any entity of `object_type`
// (vehicle, pedestrian, miscellaneous).
struct CollisionCondition {
  std::optional<std::string> entity;
  std::string object_type;
};
// RelativeClearanceCondition (1.2): no entity (of `entities`, else any other) in the lanes
// `lanes` counts from the triggering entity's (relative: 0 its own, + to the left in its
// direction of travel; none given: every lane of its road), opposite-direction lanes only
// with opposite_lanes, from distance_backward behind its reference point to distance_forward
// ahead of it along the road. The others by their reference point, or by any part of their
// bounding box with freespace. No lane there to check: false (not clear).
struct RelativeLaneRange { int from = 0, to = 0; };
struct RelativeClearanceCondition {
  std::vector<RelativeLaneRange> lanes;
  std::vector<std::string> entities;
  bool opposite_lanes = false;
  bool freespace = false;
  double distance_forward = 0, distance_backward = 0;
};
// AngleCondition (1.3): the triggering entity's heading, pitch or roll (`angle_type`) in
// `coordinate_system` is within `tolerance` of `angle` (rad; differences taken on the
// circle). world (the default): the inertial angle; road / lane: relative to the road's
// reference line / the lane's centre line where the entity is (pitch and roll relative to
// the road surface, 0 for an entity standing on it). RelativeAngleCondition (1.3): the
// triggering entity's angle minus `entity`'s, in the entity frame (the default) or world the
// plain difference, in road / lane the difference of their road-relative angles.
struct AngleCondition {
  std::string angle_type;  // heading, pitch, roll
  double angle = 0, tolerance = 0;
  std::string coordinate_system = "world";
};
struct RelativeAngleCondition {
  std::string entity;
  std::string angle_type;
  double angle = 0, tolerance = 0;
  std::string coordinate_system = "entity";
};
struct ByEntityCondition {
  bool all = false;  // triggeringEntitiesRule
  std::vector<std::string> triggering_entities;
  std::variant<SpeedCondition, RelativeDistanceCondition, TraveledDistanceCondition, StandStillCondition,
               EndOfRoadCondition, OffroadCondition, AccelerationCondition, ReachPositionCondition,
               RelativeSpeedCondition, TimeHeadwayCondition, DistanceCondition, TimeToCollisionCondition,
               CollisionCondition, RelativeClearanceCondition, AngleCondition, RelativeAngleCondition>
      condition;
};
struct Condition {
  std::string name;
  double delay = 0;
  Edge edge = Edge::None;
  std::variant<SimulationTimeCondition, StoryboardElementStateCondition, ParameterCondition, VariableCondition,
               ByEntityCondition, TrafficSignalCondition, TrafficSignalControllerCondition, TimeOfDayCondition>
      kind;
  Place place;
};
// OR over groups, AND within a group; an absent trigger is nullopt.
struct Trigger {
  std::vector<std::vector<Condition>> groups;
};

// ---- Traffic signal controllers (RoadNetwork/TrafficSignals) ------------------------
// A phase sets the states of its signals (by OpenDRIVE signal id) for `duration` seconds;
// the controller cycles through its phases, the first starting at `delay` after the start of
// the `reference` controller's first phase (after the simulation's start without one).
struct TrafficSignalPhaseState { std::string signal; std::string state; };
// TrafficSignalGroupState (1.2): one state for every signal of the controller's signal group
// (the OpenDRIVE <controller> whose id is the TrafficSignalController's name); a phase's
// TrafficSignalStates, more specific, override it for their signals.
struct TrafficSignalPhase {
  std::string name;
  double duration = 0;
  std::vector<TrafficSignalPhaseState> states;
  std::optional<std::string> group_state;
  Place group_place;  // where the TrafficSignalGroupState is written (messages)
};
struct TrafficSignalController {
  std::string name;
  double delay = 0;
  std::string reference;  // "" none
  std::vector<TrafficSignalPhase> phases;
};

// ---- Storyboard ---------------------------------------------------------------------
struct Action {
  std::string name;
  std::string key;  // unique in the storyboard: the path of names (see storyboard_reader.cpp)
  std::vector<std::string> actors;  // private actions: the maneuver group's; global actions: none
  PrivateAction action;
  Place place;
};
enum class Priority { Overwrite, Skip, Parallel };
struct Event {
  std::string name;
  std::string key;  // unique in the storyboard: the path of names (see storyboard_reader.cpp)
  Priority priority = Priority::Overwrite;
  int maximum_execution_count = 1;
  std::vector<Action> actions;
  std::optional<Trigger> start_trigger;
};
struct Maneuver {
  std::string name;
  std::string key;  // unique in the storyboard: the path of names (see storyboard_reader.cpp)
  std::vector<Event> events;
};
struct ManeuverGroup {
  std::string name;
  std::string key;  // unique in the storyboard: the path of names (see storyboard_reader.cpp)
  int maximum_execution_count = 1;
  bool select_triggering_entities = false;
  std::vector<std::string> actors;
  std::vector<Maneuver> maneuvers;
};
struct Act {
  std::string name;
  std::string key;  // unique in the storyboard: the path of names (see storyboard_reader.cpp)
  std::vector<ManeuverGroup> groups;
  std::optional<Trigger> start_trigger;
  std::optional<Trigger> stop_trigger;
};
struct Story {
  std::string name;
  std::string key;  // unique in the storyboard: the path of names (see storyboard_reader.cpp)
  std::vector<Act> acts;
};
struct InitAction {
  std::string entity;  // "" for a global action
  PrivateAction action;
  Place place;
};
struct Storyboard {
  std::vector<InitAction> init;
  std::vector<Story> stories;
  std::optional<Trigger> stop_trigger;
};

struct Scenario {
  std::string file;  // as given
  int rev_major = 1;
  int rev_minor = 0;
  std::string description;
  std::vector<Parameter> parameters;
  // Parameters of Stories and Maneuvers, named "<Story or Maneuver>/<name>" (their key in
  // ParameterSetAction, ParameterModifyAction and ParameterCondition).
  std::vector<Parameter> local_parameters;
  std::vector<Parameter> variables;  // VariableDeclarations (1.2); `type` as for parameters
  // MonitorDeclarations (1.3): boolean monitors by name with their initial values; the
  // storyboard's SetMonitorActions change them, a run reports their final values.
  std::vector<std::pair<std::string, bool>> monitors;
  std::string road_file;  // absolute path of the .xodr ("" when none)
  std::vector<TrafficSignalController> signal_controllers;  // RoadNetwork/TrafficSignals
  std::vector<Entity> entities;
  Storyboard storyboard;
  Diagnostics warnings;  // what the reader accepted but the user may want to know (missing catalog folders)
  [[nodiscard]] const Entity* entity(const std::string& name) const {
    for (const Entity& e : entities)
      if (e.name == name) return &e;
    return nullptr;
  }
};

}  // namespace orch::openscenario
