#pragma once
// Whether two runs give SUMO exactly the same commands in a step (run/fork_group.hpp shares
// SUMO between runs while they do): every field, doubles bit for bit (so 0.0 and -0.0
// differ, and a NaN equals the same NaN: what SUMO is given, not what it means).
#include <vector>

#include "sim/world.hpp"

namespace orch {

bool same_commands(const std::vector<sim::Command>& a, const std::vector<sim::Command>& b);
bool same_tracked(const std::vector<sim::TrackedActor>& a, const std::vector<sim::TrackedActor>& b);

}  // namespace orch
