#pragma once
// The verdict of a reference run (docs/reference-driver.md, "Preventable or not"): was the
// run's collision preventable (the R157 reference driver avoided that conflict), unavoidable
// (the reference driver had the same conflict), or was there none. Pure, on the two runs'
// collision facts and story events.
#include <optional>
#include <string>
#include <vector>

#include "scenario_executor_engine/engine.hpp"
#include "run/run_result.hpp"

namespace orch {

// How far apart two collisions with the same road user may be in the story and still be the
// same conflict: the reference driver brakes where the run may not, so it meets the same road
// user a little later (or earlier); seconds apart it is another conflict.
inline constexpr double kSameConflictWindow = 2.0;  // s

// Where a moment lies in the story: the story element entered last before it (a scene of a
// ScenarioExecutor scenario, "scene 2"; an OpenSCENARIO Event that started, "event
// CutInEvent") and how long before. The story's clock runs with the ego: in a reference run
// a scene may begin seconds later than in the run (4.4_2: the cut-in scene at 16.45 s and at
// 22.20 s, each collision 1.0 s into it), so a place in the story is that element and the
// time since, not the simulation time.
struct StoryPlace {
  std::string element;  // "" before any
  double since = 0;     // s
};
StoryPlace story_place(const std::vector<engine::Event>& events, double time);

// The same conflict: the same other road user, at about the same place in the story (the
// same element, within kSameConflictWindow of its start's offset) or the same time.
bool same_conflict(const CollisionFact& run, const StoryPlace& run_place, const CollisionFact& reference,
                   const StoryPlace& reference_place);

// "preventable", "unavoidable" or "no_collision" (places: the story places of the collisions;
// unknown places compare the collisions' times only).
std::string preventability(const std::optional<CollisionFact>& run, const std::optional<CollisionFact>& reference,
                           const StoryPlace& run_place = {}, const StoryPlace& reference_place = {});

}  // namespace orch
