#pragma once
// The libsumo backend as a module the program loads only when a run asks for it
// (docs/performance.md "Start-up and memory"): Debian's libsumocpp.so pulls in ~220 shared
// libraries (GDAL, FFmpeg, OpenSceneGraph, ...) whose loading and relocation cost every
// process ~0.15 s and ~45 MiB, also `validate`, `map build`, a batch's parent and a
// traci-backend run, which never call libsumo. The module (orchestrator-libsumo.so beside
// the program) holds sumo_simulator.cpp and sumo_ego_control.cpp compiled for libsumo; it
// takes everything else (errors, the run's types, the SUMO child process helpers) from the
// program, which exports its symbols for it.
#include <memory>

#include "sumo_simulator.hpp"
#include "traci_server/ego_world.hpp"

namespace orch {

// What the module hands the program. `abi` (this struct's own shape) and `build` (the build
// stamp: a hash of every header and the compiler flags, cmake/build_stamp.cmake) guard
// against a module of another build, whose types may differ in shape from the program's.
struct LibsumoModule {
  int abi;
  const char* build;
  std::unique_ptr<Simulator> (*make_simulator)(const SumoBackendOptions& options);
  std::unique_ptr<traci::EgoWorld> (*make_ego_control)();
};

// Changes whenever LibsumoModule itself changes shape (the types crossing it are covered by
// the build stamp).
inline constexpr int kLibsumoModuleAbi = 2;

}  // namespace orch

// The module's one entry point, looked up by dlsym.
extern "C" const orch::LibsumoModule* orch_libsumo_module();
