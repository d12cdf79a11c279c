// A libsumo module "of another build" for tests/e2e/test_libsumo_module_cli.cpp: the module's
// entry point with the current interface but another build stamp, as a stale
// orchestrator-libsumo.so beside a copied program has. The program must refuse it with a
// message; it never calls its factories (null here).
#include "sumo/libsumo_module.hpp"

extern "C" const orch::LibsumoModule* orch_libsumo_module() {
  static const orch::LibsumoModule module{orch::kLibsumoModuleAbi, "0000000000000000", nullptr, nullptr};
  return &module;
}
