// The backend chosen by name (`run --backend`): both client libraries are linked in.
#include <stdexcept>

#include "sumo_simulator.hpp"

namespace orch {

std::unique_ptr<Simulator> make_sumo_simulator(const std::string& backend, const SumoBackendOptions& options) {
  if (backend == "libsumo") return make_libsumo_simulator(options);
  if (backend == "traci") return make_traci_simulator(options);
  throw std::invalid_argument("unknown SUMO backend \"" + backend + "\" (libsumo or traci)");
}

}  // namespace orch
