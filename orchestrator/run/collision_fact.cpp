#include "run/collision_fact.hpp"

#include <cmath>

namespace orch {

namespace {
std::optional<double> speed_of(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked,
                               const std::string& sumo_id) {
  for (std::size_t i = 0; i < tracked.size() && i < snap.actors.size(); ++i)
    if (tracked[i].sumo_id == sumo_id) return snap.actors[i].speed;
  for (const auto& n : snap.nearby)
    if (n.sumo_id == sumo_id) return n.speed;
  return std::nullopt;
}
}  // namespace

std::optional<double> relative_speed(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked,
                                     const std::string& a, const std::string& b) {
  const auto va = speed_of(snap, tracked, a);
  const auto vb = speed_of(snap, tracked, b);
  if (!va || !vb) return std::nullopt;
  return std::abs(*va - *vb);
}

std::optional<CollisionFact> ego_collision_fact(const engine::Engine& engine, sim::ActorId ego,
                                                const sim::WorldSnapshot& snap) {
  const std::string me = std::to_string(ego);
  for (const auto& c : engine.contacts()) {
    if (!c.counted || (c.a != me && c.b != me)) continue;
    const std::string other = c.a == me ? c.b : c.a;
    CollisionFact f;
    f.with = engine.describe_body(other);
    f.time = c.time;
    // Contacts name actors by id and background vehicles by SUMO id.
    auto sumo_id = [&](const std::string& body) {
      const auto actor = engine.actor_named(body);
      if (!actor) return body;
      const auto* slot = engine.actors().find(*actor);
      return slot ? slot->tracked.sumo_id : body;
    };
    f.relative_speed = relative_speed(engine.judged(), engine.tracked(), sumo_id(me), sumo_id(other));
    if (!f.relative_speed) f.relative_speed = relative_speed(snap, engine.tracked(), sumo_id(me), sumo_id(other));
    return f;
  }
  return std::nullopt;
}

}  // namespace orch
