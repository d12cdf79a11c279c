#pragma once
// State shared by the parts of the .xosc reader (internal): the scenario's parameter scope,
// the loaded catalogs and the scopes of catalog entries (kept alive for their Elements).
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

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
  std::deque<ParameterScope> entry_scopes;

  // The catalog entry a CatalogReference names, as an Element whose scope holds the
  // entry's parameters with the reference's assignments. `kind` is the element expected
  // ("Vehicle", "Controller", ...; several allowed for entities).
  Element resolve(Element& reference, const std::vector<std::string>& kinds);
};

void read_catalog_locations(Element& locations, const std::string& scenario_dir, Context& context);

Entity read_entity(Element& scenario_object, Context& context);
Controller read_controller(Element& controller);

Position read_position(Element& position);
// The action in a PrivateAction or GlobalAction element (action_reader.cpp's tables).
PrivateAction read_private_action(Element& private_action, Context& context);
PrivateAction read_global_action(Element& global_action, Context& context);
Trigger read_trigger(Element& trigger);
Storyboard read_storyboard(Element& storyboard, const Scenario& scenario, Context& context);

// Readers of single actions used by the tables (routing_reader.cpp, global_action_reader.cpp).
AssignRouteAction read_assign_route(Element& e, Context& context);
FollowTrajectoryAction read_follow_trajectory(Element& e, Context& context);
ParameterSetAction read_parameter_set(Element& parameter_action, Element& set);
ParameterModifyAction read_parameter_modify(Element& parameter_action, Element& modify);

// Closed sets shared by several readers.
Rule read_rule(Element& e);
TransitionDynamics read_dynamics(Element& e);
DynamicsShape read_shape(Element& e);

}  // namespace orch::openscenario::reading
