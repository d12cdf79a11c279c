#include "run/openscenario_observed.hpp"

#include <algorithm>

#include "run/reference_ego_setup.hpp"

namespace orch {

OpenScenarioRun::OpenScenarioRun(const openscenario::Scenario& scenario, const opendrive::RoadNetwork& roads,
                                 const OpenScenarioActors& actors)
    : scenario_(scenario), roads_(roads), actors_(actors) {}

std::optional<sim::ActorId> OpenScenarioRun::id_of(const std::string& name) const {
  for (std::size_t i = 0; i < scenario_.entities.size(); ++i)
    if (actors_.name_of(static_cast<sim::ActorId>(i)) == name) return static_cast<sim::ActorId>(i);
  return std::nullopt;
}

std::optional<sim::ActorId> OpenScenarioRun::ego() const {
  return actors_.ego().empty() ? std::nullopt : id_of(actors_.ego());
}

std::optional<ObservedBody> OpenScenarioRun::body(sim::ActorId id) const {
  for (const sim::TrackedActor& t : actors_.tracked()) {
    if (t.id != id) continue;
    const std::string& name = actors_.name_of(t.id);
    ActorKind kind = ActorKind::Vehicle;  // SUMO has every entity as a vehicle; the metrics go by the entity
    if (const openscenario::Entity* e = scenario_.entity(name)) {
      if (e->kind == openscenario::EntityKind::Pedestrian) kind = ActorKind::Pedestrian;
      if (e->kind == openscenario::EntityKind::MiscObject) kind = ActorKind::Obstacle;
    }
    return ObservedBody{name, t.length, t.width, kind};
  }
  return std::nullopt;
}

const Polyline* OpenScenarioRun::path_of(sim::ActorId id) const {
  const auto it = paths_.find(id);
  return it == paths_.end() ? nullptr : &it->second;
}

void OpenScenarioRun::update(const sim::WorldSnapshot& snapshot, double time,
                             const std::map<std::string, openscenario::EntityState>& entities,
                             bool stop_trigger_fired) {
  snapshot_ = snapshot;
  snapshot_.time = time;
  stop_trigger_fired_ = stop_trigger_fired;
  for (const sim::TrackedActor& t : actors_.tracked()) {
    if (paths_.count(t.id)) continue;
    const auto state = entities.find(actors_.name_of(t.id));
    if (state != entities.end() && state->second.placed && !state->second.road_id.empty())
      paths_.emplace(t.id, lane_path(roads_, state->second).line);
  }
  record_contacts(snapshot, time);
}

void OpenScenarioRun::record_contacts(const sim::WorldSnapshot& snapshot, double time) {
  // Contacts name entities by run index, like ScenarioExecutor actors (criteria's `With`),
  // and other SUMO vehicles by their SUMO id.
  auto body_id = [&](const std::string& sumo_id) -> std::optional<std::string> {
    for (const sim::TrackedActor& t : actors_.tracked())
      if (t.sumo_id == sumo_id) return std::to_string(t.id);
    return std::nullopt;
  };
  auto position_of = [&](const std::string& sumo_id) {
    for (const auto& a : snapshot.actors)
      for (const sim::TrackedActor& t : actors_.tracked())
        if (t.id == a.id && t.sumo_id == sumo_id) return a.position;
    for (const auto& v : snapshot.nearby)
      if (v.sumo_id == sumo_id) return v.position;
    return Vec2{0, 0};
  };
  for (const auto& c : snapshot.collisions) {
    const auto a = body_id(c.collider), b = body_id(c.victim);
    if (!a && !b) continue;  // background vehicles among themselves
    engine::Contact contact;
    contact.time = time;
    contact.a = a.value_or(c.collider);
    contact.b = b.value_or(c.victim);
    if (!touched_.insert(std::minmax(contact.a, contact.b)).second) continue;
    contact.position_a = position_of(c.collider);
    contact.position_b = position_of(c.victim);
    contact.source = "sumo";
    contact.sumo_type = c.type;
    contacts_.push_back(std::move(contact));
  }
}

}  // namespace orch
