#pragma once
// Simulator implementations on SUMO. One source (sumo_simulator.cpp) is compiled once per
// SUMO client library: libsumo runs SUMO inside this process (fastest; one simulation per
// process), libtraci drives a separate sumo or sumo-gui process over TraCI (README
// "Backends").
#include <memory>
#include <string>

#include "run/simulator.hpp"

namespace orch {

// What only the traci backend uses; libsumo ignores it.
struct SumoBackendOptions {
  bool gui = false;       // start sumo-gui instead of sumo (it starts running and quits at the end)
  std::string connect;    // "host:port" of a SUMO started elsewhere with --remote-port; empty: start one
  // s without an answer from SUMO before the run ends with verdict error (a hung SUMO);
  // 0 waits forever (e.g. while the simulation is paused in sumo-gui).
  double reply_timeout = 10;
  double startup_timeout = 60;  // s for SUMO to load the net and accept the connection
};

std::unique_ptr<Simulator> make_libsumo_simulator(const SumoBackendOptions& options = {});
std::unique_ptr<Simulator> make_traci_simulator(const SumoBackendOptions& options = {});

// "libsumo" or "traci"; throws std::invalid_argument for anything else.
std::unique_ptr<Simulator> make_sumo_simulator(const std::string& backend, const SumoBackendOptions& options = {});

}  // namespace orch
