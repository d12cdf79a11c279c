// The module's entry point (libsumo_module.hpp). Compiled into orchestrator-libsumo.so only.
#include "libsumo_module.hpp"

#include "libsumo_build_stamp.hpp"

#include "sumo_ego_control.hpp"

extern "C" const orch::LibsumoModule* orch_libsumo_module() {
  static const orch::LibsumoModule module{orch::kLibsumoModuleAbi, ORCH_LIBSUMO_BUILD_STAMP, &orch::make_libsumo_simulator,
                                          &orch::make_ego_control_libsumo};
  return &module;
}
