#pragma once
// State shared by the parts of the .xosc reader (internal): the scenario's parameter scope,
// the loaded catalogs and the scopes of catalog entries (kept alive for their Elements).
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "openscenario/element_reader.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario::reading {

struct CatalogEntry {
  const xml::XmlSource* source = nullptr;
  pugi::xml_node node;
};

class Context {
 public:
  ParameterScope global;
  std::vector<std::unique_ptr<xml::XmlSource>> catalog_files;
  // catalog name -> entry name -> entry
  std::map<std::string, std::map<std::string, CatalogEntry>> catalogs;
  std::deque<ParameterScope> entry_scopes;  // of catalog entries, Stories, Maneuvers, inline objects
  // Parameters of Stories and Maneuvers, named by their runtime key ("<owner>/<name>").
  std::vector<Parameter> local_parameters;
  std::vector<Parameter> variables;  // VariableDeclarations (1.2)
  std::vector<std::string> monitors;  // MonitorDeclarations (1.3), by name
  std::vector<TrafficSignalController> signal_controllers;  // RoadNetwork/TrafficSignals, read first
  // Catalog kinds whose Directory does not exist: kind -> directory (a reference into it is
  // the error, the missing directory only a warning).
  std::map<std::string, std::string> missing_catalog_directories;
  Diagnostics warnings;
  // TrafficActions: the trafficNames they define, and each TrafficStopAction's name with its
  // TrafficAction (checked against them once the storyboard is read).
  std::vector<std::string> traffic_names;
  std::vector<std::pair<std::string, Element>> traffic_stops;

  // The catalog entry a CatalogReference names, as an Element whose scope holds the
  // entry's parameters with the reference's assignments. `kind` is the element expected
  // ("Vehicle", "Controller", ...; several allowed for entities).
  Element resolve(Element& reference, const std::vector<std::string>& kinds);

 private:
  std::map<std::string, std::map<std::string, CatalogEntry>>::iterator find_by_kind(
      Element& reference, const std::string& catalog_name, const std::string& entry_name,
      const std::vector<std::string>& kinds);
};

// One ParameterDeclaration ("parameterType") or VariableDeclaration ("variableType").
Parameter read_declaration(Element& declaration, const char* type_attribute = "parameterType");
// `owner` read in a new scope holding its ParameterDeclarations (owner itself when it has
// none). With a `key_prefix` the parameters are the storyboard's too (Story, Maneuver):
// they join context.local_parameters as "<key_prefix>/<name>".
Element open_scope(Element& owner, Context& context, const std::string& key_prefix);
// The runtime key of the parameter `name` visible at `at` (a ParameterAction's or
// ParameterCondition's), with its type; fails when none is declared or the runtime does not
// hold it (a catalog entry's).
std::pair<std::string, std::string> runtime_parameter(Element& at, const char* attribute);

void read_catalog_locations(Element& locations, const std::string& scenario_dir, Context& context);

// The entity, then the trailers written inline in it (named "<entity>+", "<entity>++", ...).
std::vector<Entity> read_entity(Element& scenario_object, Context& context);
// A ScenarioObjectTemplate (1.3: an entity without a name, as in an EntityDistribution).
std::vector<Entity> read_entity_template(Element& object_template, Context& context);
Controller read_controller(Element& controller);

Position read_position(Element& position);
// A RoutePosition's RouteRef (an inline Route or a CatalogReference to one).
std::shared_ptr<const position::RouteWaypoints> read_route_ref(Element& route_ref, Context& context);
// The Context of the file being read, for read_position (a RoutePosition's route may be a
// catalog entry), which its many callers call without one: set by load_scenario for the
// whole read, per thread.
class ContextInUse {
 public:
  explicit ContextInUse(Context& context);
  ~ContextInUse();
  ContextInUse(const ContextInUse&) = delete;
  ContextInUse& operator=(const ContextInUse&) = delete;

 private:
  Context* previous_;
};
// The action in a PrivateAction or GlobalAction element (action_reader.cpp's tables).
PrivateAction read_private_action(Element& private_action, Context& context);
PrivateAction read_global_action(Element& global_action, Context& context);
Trigger read_trigger(Element& trigger, const Context& context);
Storyboard read_storyboard(Element& storyboard, const Scenario& scenario, Context& context);

// Readers of single actions used by the tables (routing_reader.cpp, global_action_reader.cpp).
AssignRouteAction read_assign_route(Element& e, Context& context);
FollowTrajectoryAction read_follow_trajectory(Element& e, Context& context);
// A TrajectoryRef's Trajectory, inline or from a catalog (FollowTrajectoryAction, TrajectoryPosition).
Trajectory read_trajectory_ref(Element& trajectory_ref, Context& context);
ParameterSetAction read_parameter_set(Element& parameter_action, Element& set);
ParameterModifyAction read_parameter_modify(Element& parameter_action, Element& modify);
AppearanceAction read_light_state(Element& light_state_action);
AppearanceAction read_animation(Element& animation_action, Context& context);
// override_reader.cpp: ControllerAction/OverrideControllerValueAction, UserDefinedAction
// (element "CustomCommandAction": no actors). Both run with no effect on motion.
AppearanceAction read_controller_override(Element& override_action, Context& context);
AppearanceAction read_user_defined_action(Element& user_defined_action, Context& context);
EnvironmentAction read_environment_action(Element& environment_action, Context& context);
// An xsd:dateTime attribute (TimeOfDay, TimeOfDayCondition) as openscenario/date_time.hpp reads it.
double read_date_time(Element& e, const char* attribute);
VariableSetAction read_variable_set(Element& variable_action, Element& set, const Context& context);
VariableModifyAction read_variable_modify(Element& variable_action, Element& modify, const Context& context);
// The declared variable `variableRef` names, with its type (VariableAction, VariableCondition).
std::pair<std::string, std::string> declared_variable(Element& at, const Context& context);

// Traffic signals (traffic_signal_reader.cpp): RoadNetwork/TrafficSignals, the
// InfrastructureAction's TrafficSignalAction, the two conditions; controller and phase
// names checked against context.signal_controllers.
std::vector<TrafficSignalController> read_traffic_signals(Element& traffic_signals);
PrivateAction read_traffic_signal_action(Element& traffic_signal_action, const Context& context);
TrafficSignalCondition read_traffic_signal_condition(Element& e);
TrafficSignalControllerCondition read_traffic_signal_controller_condition(Element& e, const Context& context);
LateralDistanceAction read_lateral_distance(Element& e);
// GlobalAction/TrafficAction (traffic_action_reader.cpp); check_traffic_stops fails on a
// TrafficStopAction whose trafficName no TrafficAction of the file defines.
PrivateAction read_traffic_action(Element& traffic_action, Element& action, Context& context);
void check_traffic_stops(const Context& context);

// Closed sets shared by several readers.
Rule read_rule(Element& e);
TransitionDynamics read_dynamics(Element& e, Context& context);
DynamicsShape read_shape(Element& e);

}  // namespace orch::openscenario::reading
