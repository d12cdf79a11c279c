#pragma once
// A ScenarioExecutor run as its observers see it: the scene graph's engine.
#include "run/run_observer.hpp"

namespace orch {

class EngineRun : public ObservedRun {
 public:
  explicit EngineRun(const engine::Engine& engine) : engine_(engine) {}
  [[nodiscard]] const sim::WorldSnapshot& judged() const override { return engine_.judged(); }
  [[nodiscard]] std::optional<sim::ActorId> ego() const override;
  [[nodiscard]] std::optional<ObservedBody> body(sim::ActorId id) const override;
  [[nodiscard]] const Polyline* path_of(sim::ActorId id) const override;
  [[nodiscard]] int scene() const override { return engine_.scene(); }
  [[nodiscard]] bool ending_reached() const override { return engine_.state() == engine::RunState::EndingReached; }
  [[nodiscard]] const std::vector<engine::SceneVisit>& visits() const override { return engine_.visits(); }
  [[nodiscard]] const std::vector<engine::Contact>& contacts() const override { return engine_.contacts(); }

 private:
  const engine::Engine& engine_;
};

}  // namespace orch
