#include "scenario_executor_engine/scene_machine.hpp"

namespace orch::engine {

SceneMachine::SceneMachine(const scenario::Scenario& s)
    : scenario_(s), next_(&s.opening.next_scenes) {
  visits_.push_back({scenario::kOpeningSceneId, "opening scene", 0.0});
}

std::optional<Transition> SceneMachine::step(double t, const std::function<bool(const scenario::Scene&)>& holds) {
  if (ended_) return std::nullopt;
  if (t - entered_at_ < duration_ - 1e-9) return std::nullopt;
  for (scenario::SceneId id : *next_) {
    const scenario::Scene* scene = scenario_.find_scene(id);
    if (!scene || !holds(*scene)) continue;
    Transition tr{current_, scene};
    current_ = scene->id;
    entered_at_ = t;
    duration_ = scene->duration;
    next_ = &scene->next_scenes;
    ended_ = scene->ending;
    visits_.push_back({scene->id, scene->description, t});
    return tr;
  }
  return std::nullopt;
}

}  // namespace orch::engine
