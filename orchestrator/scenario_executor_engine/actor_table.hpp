#pragma once
// The scenario's actors as the run knows them: ids, SUMO ids, kinds and sizes.
#include <string>
#include <vector>

#include "scenario_executor_engine/sim_names.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/model.hpp"

namespace orch::engine {

struct ActorSlot {
  TrackedActor tracked;
  ModelInfo model;
  scenario::ActorSpec spec;
  [[nodiscard]] bool is_ego() const { return spec.is_ego; }
};

class ActorTable {
 public:
  // Ego first, then the others in file order. Throws ScenarioError for an unknown model.
  ActorTable(const scenario::Scenario& s, const Catalog& catalog);

  [[nodiscard]] const std::vector<ActorSlot>& slots() const { return slots_; }
  [[nodiscard]] const ActorSlot* find(ActorId id) const;
  [[nodiscard]] const ActorSlot* find_sumo(const std::string& sumo_id) const;
  [[nodiscard]] std::vector<TrackedActor> tracked() const;

  // The documented SUMO id scheme: "ego" for the ego, "actor<id>" for every other actor.
  static std::string sumo_id_for(const scenario::ActorSpec& spec);

 private:
  std::vector<ActorSlot> slots_;
};

}  // namespace orch::engine
