// The scene graph (ids, next_scenes, what can be reached and how a run can end) and start
// positions given relative to other actors.
#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <map>
#include <set>

#include "scenario_executor/validator_internal.hpp"

namespace orch::scenario_checks {

using namespace orch::scenario;

namespace {

std::string scene_id_list(const Scenario& s) {
  std::string out;
  for (const auto& scene : s.scenes) out += (out.empty() ? "" : ", ") + std::to_string(scene.id);
  return out.empty() ? "none" : out;
}

void check_scene_ids(CheckContext& ctx) {
  std::map<SceneId, const Scene*> seen;
  for (const auto& scene : ctx.s.scenes) {
    if (scene.id == kOpeningSceneId) {
      ctx.diags.error(scene.where, fmt::format("scene_id {} is the opening scene's id (in logs and results); use "
                                               "another number",
                                               kOpeningSceneId));
      continue;
    }
    auto [it, inserted] = seen.emplace(scene.id, &scene);
    if (!inserted)
      ctx.diags.error(scene.where, fmt::format("scene_id {} is used twice (scene ids are shared by \"scenes\" and "
                                               "\"ending_scenes\"); the first is at line {}",
                                               scene.id, it->second->where.line));
  }
}

// next_scenes of the opening scene or of one scene: targets exist, no repeats, not empty.
void check_next_scenes(CheckContext& ctx, const std::vector<SceneId>& next, const SourceLocation& where,
                       const std::string& owner) {
  std::set<SceneId> seen;
  for (SceneId id : next) {
    if (!seen.insert(id).second) {
      ctx.diags.warning(where, fmt::format("next_scenes of {} names scene {} twice", owner, id));
      continue;
    }
    if (!ctx.s.find_scene(id) || id == kOpeningSceneId)
      ctx.diags.error(where, fmt::format("next_scenes of {} names scene {}, which is not defined (scene ids: {})",
                                         owner, id, scene_id_list(ctx.s)));
  }
  if (next.empty())
    ctx.diags.error(where, fmt::format("{} has no next_scenes: once entered it can never be left (give it "
                                       "next_scenes, or make it an ending scene)",
                                       owner));
}

// Scenes reachable from the opening scene through next_scenes.
std::set<SceneId> reachable_scenes(const Scenario& s) {
  std::set<SceneId> seen;
  std::deque<SceneId> todo(s.opening.next_scenes.begin(), s.opening.next_scenes.end());
  while (!todo.empty()) {
    const SceneId id = todo.front();
    todo.pop_front();
    const Scene* scene = s.find_scene(id);
    if (!scene || !seen.insert(id).second) continue;
    todo.insert(todo.end(), scene->next_scenes.begin(), scene->next_scenes.end());
  }
  return seen;
}

// Scenes from which some ending scene can be reached (ending scenes included).
std::set<SceneId> scenes_that_can_end(const Scenario& s) {
  std::set<SceneId> can_end;
  for (const auto& scene : s.scenes)
    if (scene.ending) can_end.insert(scene.id);
  for (bool grew = true; grew;) {  // a fixed point; scene graphs are small
    grew = false;
    for (const auto& scene : s.scenes) {
      if (can_end.count(scene.id)) continue;
      const bool leads_to_end = std::any_of(scene.next_scenes.begin(), scene.next_scenes.end(),
                                            [&](SceneId n) { return can_end.count(n) > 0; });
      if (leads_to_end) grew = can_end.insert(scene.id).second || grew;
    }
  }
  return can_end;
}

}  // namespace

void check_scene_graph(CheckContext& ctx) {
  const Scenario& s = ctx.s;
  check_scene_ids(ctx);
  check_next_scenes(ctx, s.opening.next_scenes, s.opening.where, "the opening scene");
  for (const auto& scene : s.scenes)
    if (!scene.ending) check_next_scenes(ctx, scene.next_scenes, scene.where, fmt::format("scene {}", scene.id));

  const auto reachable = reachable_scenes(s);
  for (const auto& scene : s.scenes) {
    if (scene.id != kOpeningSceneId && !reachable.count(scene.id))
      ctx.diags.error(scene.where, fmt::format("{} {} can never be reached: no next_scenes leads to it from the "
                                               "opening scene",
                                               scene.ending ? "ending scene" : "scene", scene.id));
  }

  const bool any_ending = std::any_of(s.scenes.begin(), s.scenes.end(), [](const Scene& sc) { return sc.ending; });
  const bool ending_reachable = std::any_of(s.scenes.begin(), s.scenes.end(), [&](const Scene& sc) {
    return sc.ending && reachable.count(sc.id) > 0;
  });
  if (!any_ending) {
    ctx.diags.error(s.opening.where, "the scenario has no ending scene: add \"ending_scenes\" to \"scenario\" so "
                                     "that a run can end");
    return;
  }
  if (!ending_reachable) {
    ctx.diags.error(s.opening.where, "no ending scene can be reached from the opening scene, so a run could only "
                                     "end by stop_conditions");
    return;
  }
  // Reachable scenes from which no path leads to an ending scene: only stop_conditions
  // can end a run that enters them. Legal, but rarely meant.
  const auto can_end = scenes_that_can_end(s);
  for (const auto& scene : s.scenes) {
    if (reachable.count(scene.id) && !can_end.count(scene.id) && !scene.next_scenes.empty())
      ctx.diags.warning(scene.where, fmt::format("no ending scene can be reached from scene {}: a run that enters it "
                                                 "ends only by stop_conditions",
                                                 scene.id));
  }
}

void check_start_cycles(CheckContext& ctx) {
  // actor -> the actor its start position is measured from
  std::map<ActorId, ActorId> relative_to;
  std::map<ActorId, const StartPosition*> start_of;
  for (const auto& entry : ctx.s.opening.others) {
    if (entry.start.type != StartPositionType::Distance || !entry.start.target) continue;
    if (*entry.start.target == entry.actor) {
      ctx.diags.error(entry.start.where, fmt::format("the start position of actor {} is measured from the actor "
                                                     "itself; name another actor in \"target_actor_id\"",
                                                     entry.actor));
      continue;
    }
    relative_to.emplace(entry.actor, *entry.start.target);
    start_of.emplace(entry.actor, &entry.start);
  }
  std::set<ActorId> reported;
  for (const auto& [first, ignored] : relative_to) {
    // Follow the chain; a cycle exists when it comes back to an actor on the chain.
    std::vector<ActorId> chain{first};
    for (auto it = relative_to.find(first); it != relative_to.end(); it = relative_to.find(it->second)) {
      const auto again = std::find(chain.begin(), chain.end(), it->second);
      if (again == chain.end()) {
        chain.push_back(it->second);
        continue;
      }
      std::vector<ActorId> cycle(again, chain.end());
      const ActorId smallest = *std::min_element(cycle.begin(), cycle.end());
      if (reported.insert(smallest).second) {
        std::rotate(cycle.begin(), std::find(cycle.begin(), cycle.end(), smallest), cycle.end());
        std::string text;
        for (ActorId a : cycle) text += fmt::format("{} -> ", a);
        text += std::to_string(cycle.front());
        ctx.diags.error(start_of.at(smallest)->where,
                        fmt::format("start positions of type \"distance\" form a cycle ({}): one of them must "
                                    "be a waypoint",
                                    text));
      }
      break;
    }
  }
}

}  // namespace orch::scenario_checks
