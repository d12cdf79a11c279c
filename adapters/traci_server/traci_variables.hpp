#pragma once
// The one list of what the ego plug-in's TraCI server serves (docs/ego-plugin.md's table is
// checked against it by a unit test): per domain, the variables a plug-in may read, with the
// name of the TraCI client function that reads them, and the ego's setters. The session
// names commands from it, the SUMO side (adapters/sumo/sumo_ego_control.cpp) answers
// supports() from it, and the documentation lists it.
#include <span>

#include "traci_server/ego_world.hpp"

namespace orch::traci {

struct ServedVariable {
  Domain domain;
  int variable;        // libsumo::VAR_*
  const char* getter;  // the client's function: "getSpeed"
  // Read through EgoWorld::read. False: served by the session from another variable
  // (getParameterWithKey from getParameter).
  bool read_from_world = true;
};

struct ServedSetter {
  int variable;      // libsumo::VAR_* / CMD_* of a vehicle set command
  const char* name;  // "setSpeed"
};

// Every variable served, domain by domain, in the order the documentation lists them.
std::span<const ServedVariable> served_variables();
// The ego's set commands (vehicle domain), in the documentation's order.
std::span<const ServedSetter> served_setters();
// Whether EgoWorld::read serves the variable in the domain.
[[nodiscard]] bool world_reads(Domain domain, int variable);
// The client function's name of a get command's variable, for messages: the simulation's,
// else the vehicle's or person's; nullptr when the server knows none.
[[nodiscard]] const char* getter_name(bool simulation, int variable);
[[nodiscard]] const char* setter_name(int variable);

}  // namespace orch::traci
