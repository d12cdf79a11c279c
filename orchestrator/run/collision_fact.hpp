#pragma once
// result.json's "collision": the ego's first collision, with whom, when and at what speed
// difference, taken from the snapshot of the step it happened in (both scenario formats).
#include <optional>
#include <string>
#include <vector>

#include "scenario_executor_engine/engine.hpp"
#include "run/run_result.hpp"

namespace orch {

// The speed difference of two SUMO ids (tracked actors or nearby background vehicles) in
// `snap`; nullopt when either is not in it.
std::optional<double> relative_speed(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked,
                                     const std::string& a, const std::string& b);

// ScenarioExecutor runs: the ego's first counted contact so far, if any, with the speeds of
// the engine's judged snapshot (scripted actors carry their commanded speed).
std::optional<CollisionFact> ego_collision_fact(const engine::Engine& engine, sim::ActorId ego,
                                                const sim::WorldSnapshot& snap);

}  // namespace orch
