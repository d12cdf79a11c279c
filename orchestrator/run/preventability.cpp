#include "run/preventability.hpp"

#include <cmath>

namespace orch {

StoryPlace story_place(const std::vector<engine::Event>& events, double time) {
  StoryPlace place;
  for (const auto& e : events) {
    if (e.time > time + 1e-9) break;  // events are in time order
    std::string element;
    if (e.kind == engine::EventKind::Scene && e.scene) {
      element = "scene " + std::to_string(*e.scene);
    } else if (e.kind == engine::EventKind::Storyboard && e.text.rfind("event ", 0) == 0) {
      // "event CutInEvent startTransition": an OpenSCENARIO Event began.
      const auto end = e.text.find(" startTransition");
      if (end == std::string::npos) continue;
      element = e.text.substr(0, end);
    } else {
      continue;
    }
    place = {element, time - e.time};
  }
  return place;
}

bool same_conflict(const CollisionFact& run, const StoryPlace& run_place, const CollisionFact& reference,
                   const StoryPlace& reference_place) {
  if (run.with != reference.with) return false;
  if (std::abs(run.time - reference.time) <= kSameConflictWindow) return true;
  return !run_place.element.empty() && run_place.element == reference_place.element &&
         std::abs(run_place.since - reference_place.since) <= kSameConflictWindow;
}

std::string preventability(const std::optional<CollisionFact>& run, const std::optional<CollisionFact>& reference,
                           const StoryPlace& run_place, const StoryPlace& reference_place) {
  if (!run) return "no_collision";
  // Unavoidable only when the careful driver could not avoid this very conflict; a collision
  // of its own elsewhere in the story says nothing about this one.
  return reference && same_conflict(*run, run_place, *reference, reference_place) ? "unavoidable" : "preventable";
}

}  // namespace orch
