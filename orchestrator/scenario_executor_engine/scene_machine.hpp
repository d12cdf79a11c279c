#pragma once
// Which scene the scenario is in. Rules (as the ScenarioExecutor reference runs them):
// - a scene is held for its `duration` before its next_scenes are tried;
// - next_scenes are tried in the order written; the first whose conditions hold is entered;
// - at most one transition per step, so every scene's actions get at least one step;
// - entering an ending scene ends the run.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "scenario_executor/model.hpp"

namespace orch::engine {

struct SceneVisit {
  scenario::SceneId id = 0;
  std::string description;
  double enter_time = 0;
};

struct Transition {
  scenario::SceneId from = 0;
  const scenario::Scene* to = nullptr;
};

class SceneMachine {
 public:
  explicit SceneMachine(const scenario::Scenario& s);

  // Tries the current scene's next_scenes at time t; `holds` evaluates a scene's conditions.
  std::optional<Transition> step(double t, const std::function<bool(const scenario::Scene&)>& holds);

  [[nodiscard]] scenario::SceneId current() const { return current_; }
  [[nodiscard]] bool ended() const { return ended_; }
  [[nodiscard]] const std::vector<SceneVisit>& visits() const { return visits_; }

 private:
  const scenario::Scenario& scenario_;
  scenario::SceneId current_ = scenario::kOpeningSceneId;
  double entered_at_ = 0;
  double duration_ = 0;
  const std::vector<scenario::SceneId>* next_;
  bool ended_ = false;
  std::vector<SceneVisit> visits_;
};

}  // namespace orch::engine
