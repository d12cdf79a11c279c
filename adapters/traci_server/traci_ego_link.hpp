#pragma once
// The EgoLink on standard TraCI: a TraCI server (Boost.Asio, in the orchestrator's thread)
// that one external ego plug-in connects to with any TraCI client (SUMO's Python traci,
// libtraci, its own). The orchestrator alone talks to SUMO and advances the world; the
// plug-in's queries are answered and its ego commands applied through an EgoWorld.
#include <atomic>
#include <memory>
#include <string>

#include "run/ego_link.hpp"
#include "traci_server/ego_world.hpp"

namespace orch::traci {

struct EgoServerOptions {
  std::string address = "127.0.0.1";  // loopback unless asked otherwise: TraCI has no authentication
  int port = 0;                        // 0: any free port (the run log names it)
  double wait_s = 60;                  // how long the first step waits for the plug-in to connect
  double timeout_s = 30;               // how long the world waits for the plug-in's next message
  double close_grace_s = 2;            // after the run: how long the plug-in may take to say close
  const std::atomic<bool>* interrupted = nullptr;  // Ctrl-C ends every wait
};

std::unique_ptr<EgoLink> make_traci_ego_link(const EgoServerOptions& options, std::unique_ptr<EgoWorld> world);

}  // namespace orch::traci
