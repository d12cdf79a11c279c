#include "scenario_executor_engine/actor_table.hpp"

#include "core/errors.hpp"

namespace orch::engine {

std::string ActorTable::sumo_id_for(const scenario::ActorSpec& spec) {
  return spec.is_ego ? std::string("ego") : "actor" + std::to_string(spec.id);
}

ActorTable::ActorTable(const scenario::Scenario& s, const Catalog& catalog) {
  auto add = [&](const scenario::ActorSpec& spec) {
    const ModelInfo* model = catalog.find(spec.model_id);
    if (!model) throw ScenarioError(spec.where, "unknown model_id \"" + spec.model_id + "\"");
    ActorSlot slot;
    slot.spec = spec;
    slot.model = *model;
    slot.tracked = {spec.id, sumo_id_for(spec), model->kind, model->length, model->width};
    slots_.push_back(std::move(slot));
  };
  add(s.ego);
  for (const auto& o : s.others) add(o);
}

const ActorSlot* ActorTable::find(ActorId id) const {
  for (const auto& s : slots_)
    if (s.spec.id == id) return &s;
  return nullptr;
}

const ActorSlot* ActorTable::find_sumo(const std::string& sumo_id) const {
  for (const auto& s : slots_)
    if (s.tracked.sumo_id == sumo_id) return &s;
  return nullptr;
}

std::vector<TrackedActor> ActorTable::tracked() const {
  std::vector<TrackedActor> out;
  for (const auto& s : slots_) out.push_back(s.tracked);
  return out;
}

}  // namespace orch::engine
