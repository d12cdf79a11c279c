#include "run/engine_run.hpp"

namespace orch {

std::optional<sim::ActorId> EngineRun::ego() const {
  for (const auto& slot : engine_.actors().slots())
    if (slot.is_ego()) return slot.spec.id;
  return std::nullopt;
}

std::optional<ObservedBody> EngineRun::body(sim::ActorId id) const {
  const engine::ActorSlot* slot = engine_.actors().find(id);
  if (!slot) return std::nullopt;
  return ObservedBody{std::to_string(id), slot->model.length, slot->model.width, slot->tracked.kind};
}

const Polyline* EngineRun::path_of(sim::ActorId id) const {
  const WaypointRoute* route = engine_.route_of(id);
  return route ? &route->line : nullptr;
}

}  // namespace orch
