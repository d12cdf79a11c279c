#pragma once
// Simulator implementations on SUMO. One source (sumo_simulator.cpp) is compiled once per
// SUMO client library: libsumo runs SUMO inside this process (fastest; one simulation per
// process), libtraci drives a separate sumo process over TraCI.
#include <memory>

#include "run/simulator.hpp"

namespace orch {

std::unique_ptr<Simulator> make_libsumo_simulator();

}  // namespace orch
