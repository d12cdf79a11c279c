#pragma once
// The SUMO side of the ego plug-in: answers the TraCI server's reads from SUMO and applies
// the plug-in's ego commands to SUMO. One source (sumo_ego_control.cpp), compiled once per
// SUMO client library like sumo_simulator.cpp, so that a plug-in sees the same world on the
// libsumo and the traci backend. Use it with the simulator of the same backend: both talk
// to the process's one SUMO (libsumo) or to its one default TraCI connection (libtraci).
#include <memory>

#include "traci_server/ego_world.hpp"

namespace orch {

std::unique_ptr<traci::EgoWorld> make_ego_control_libsumo();
std::unique_ptr<traci::EgoWorld> make_ego_control_libtraci();

}  // namespace orch
