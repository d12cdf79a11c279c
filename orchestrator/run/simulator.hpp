#pragma once
// The seam to the traffic simulator. The only implementations that talk to SUMO live in
// adapters/ (libsumo in-process, libtraci over a socket); tests of pure logic use a fake.
// Implementations turn SUMO's sentinel values and exceptions into the project's types:
// SimulationError carries SUMO's own message.
#include <memory>
#include <string>
#include <vector>

#include "sim/world.hpp"

namespace orch {

struct SimulatorConfig {
  std::string net_file;
  double step = 0.05;       // s
  long long seed = 42;
  std::string log_file;     // SUMO's own messages go here, not to the terminal
  // SUMO route files with background traffic (docs/background-traffic.md); empty: none.
  std::vector<std::string> route_files;
  std::vector<std::string> extra_args;  // appended to SUMO's command line
};

class Simulator {
 public:
  virtual ~Simulator() = default;
  virtual void start(const SimulatorConfig& config) = 0;
  virtual void apply(const std::vector<sim::Command>& commands) = 0;
  virtual void advance() = 0;  // one step
  // The tracked actors' state now (same order); background vehicles near them
  // (WorldSnapshot::nearby) and the number of all others. Its cost must not grow with the
  // number of background vehicles (docs/performance.md).
  virtual sim::WorldSnapshot read(const std::vector<sim::TrackedActor>& actors) = 0;
  virtual double time() = 0;
  [[nodiscard]] virtual std::string backend() const = 0;  // "libsumo", "traci"
  virtual std::string version() = 0;                      // "SUMO 1.15.0"
  virtual void close() = 0;
};

// SUMO's command line as the orchestrator runs it (both backends): fixed step, recorded
// seed, collisions reported but nobody teleported or removed, sublane model on so that
// lateral offsets are real.
std::vector<std::string> sumo_arguments(const SimulatorConfig& c);

}  // namespace orch
