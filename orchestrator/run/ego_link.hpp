#pragma once
// The seam to an external ego plug-in (ARCHITECTURE.md "One seam per outside system").
// The system under test drives the ego in lockstep: every step the runner reads the world,
// the engine decides, and then the link lets the plug-in look and act until it asks the
// world to advance. The implementation (a TraCI server on Boost.Asio) lives in
// adapters/traci_server; this header is plain C++ so that the core never sees sockets.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "sim/world.hpp"

namespace orch {

// The plug-in left, stopped answering, or broke the protocol. Ends the run with verdict
// `error` (it is the test bench that failed, not the system under test's driving).
class EgoError : public OrchError {
 public:
  using OrchError::OrchError;
};

// What result.json says about the plug-in's connection ("ego_plugin").
struct EgoLinkReport {
  std::string listen;             // address:port the server listened on
  std::string peer;               // address:port of the plug-in; "" if none connected
  std::string client;             // what the plug-in said it is (simulation parameter "orch.client"), or ""
  std::optional<int> order;       // setOrder, if sent
  std::optional<double> connected_at;  // simulation time of the first command
  long long steps_driven = 0;     // world steps taken at the plug-in's request
  std::string end;                // how the connection ended: "closed by the plug-in", "disconnected", ...
  std::map<std::string, long long> commands;  // "vehicle.setSpeed" -> how often
};

class EgoLink {
 public:
  virtual ~EgoLink() = default;
  // Opens the listening socket and says where, for the run log. Called before SUMO starts,
  // so that a plug-in may connect while SUMO loads and a taken port fails the run at once.
  virtual std::string listen() = 0;
  // Called every step once the world is read and this step's scenario commands are applied
  // (so a hand_over is visible). The first call waits for the plug-in to connect. Serves the
  // plug-in's queries and commands and returns when the world may advance one step. While a
  // simulationStep to a later target time is under way it returns at once. Throws EgoError
  // when the plug-in disconnects, times out or breaks the protocol.
  virtual void exchange(double time) = 0;
  // The run is over (whatever ended it): answers a pending simulationStep, gives the plug-in
  // a short, bounded chance to close, and closes the connection. Never throws.
  virtual void finish(const std::string& verdict, const std::string& reason) noexcept = 0;
  // True while a plug-in is connected and drives the ego.
  [[nodiscard]] virtual bool driving() const = 0;
  [[nodiscard]] virtual EgoLinkReport report() const = 0;
};

// The ego's SUMO id; the plug-in may command only this vehicle.
inline constexpr const char* kEgoSumoId = "ego";

// SUMO's lane-change mode for an ego the plug-in drives: SUMO's default (1621) without the
// lane changes SUMO would make on its own (strategic, cooperative, speed gain, keep right),
// so the ego changes lanes only when the plug-in says so.
inline constexpr int kPluginEgoLaneChangeMode = 1621 & ~0xFF;

// The ego's actor id when a connected plug-in drives it this step (for the trace's
// `driver` column), else nullopt.
std::optional<sim::ActorId> plugin_driven_actor(const EgoLink* link,
                                                     const std::vector<sim::TrackedActor>& tracked);

// One line for the run log: who connected, how it ended, what it used most.
std::string describe(const EgoLinkReport& report);

}  // namespace orch
