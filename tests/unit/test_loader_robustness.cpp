// Bad input never crashes the loader or the checks: every value of a valid scenario is
// replaced by every JSON type in turn, and every key is removed in turn.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "scenario_executor/loader_internal.hpp"
#include "test_loader_support.hpp"

using namespace orch;
using namespace orch::loader_test;

namespace {

// A scenario that uses most of the format, so that most readers see bad values.
std::string rich_scenario() {
  return with_scene(R"({"scene_id": 1, "description": "d", "duration": 1,
"conditions": {"and": [{"distance": {"actor_id": 1, "type": "straight", "target_actor_id": 0, "comparison": "<", "value": 3, "measure_type": "surface"}},
                       {"or": [{"position": {"actor_id": 1, "type": "reach", "wp_id": "Waypoint01", "wp_idx": 40, "tolerance": 1}},
                               {"time_headway": {"actor_id": 0, "wp_id": "Waypoint02", "wp_idx": 90, "comparison": "<=", "value": 2}}]}],
               "or": [{"speed": {"actor_id": 1, "type": "relative", "target_actor_id": 0, "comparison": ">", "value": 1}}]},
"actions": [{"speed": {"actor_id": 1, "type": "absolute", "value": 50, "accel": {"type": "specify", "value": 2}}},
            {"traveled_distance": {"actor_id": 1, "target_actor_id": 0, "value": 10, "measure_type": "center"}},
            {"lane_change": {"actor_id": 1, "type": "lane", "wp_id": "Waypoint02", "time": 3}},
            {"lane_offset": {"actor_id": 1, "value": 0.5, "time": 1}},
            {"route_move": {"actor_id": 2, "type": "waypoint", "route": [{"time": 3, "wp_id": "Waypoint03", "wp_idx": 60, "wp_offset": 1}]}},
            {"light_state": {"actor_id": 1, "blinker_left": true, "blinker_right": false, "special1": false}},
            {"sound_state": {"actor_id": 1, "sound": false}},
            {"hand_over": {"actor_id": 0, "hand_over": true, "throttle": 0.2, "brake": 0, "steer": 0}}],
"next_scenes": [9]})");
}

// Every JSON pointer in the document (objects' keys and arrays' elements).
void collect_pointers(const nlohmann::json& v, const std::string& pointer, std::vector<std::string>& out) {
  out.push_back(pointer);
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) collect_pointers(*it, json_pointer_child(pointer, it.key()), out);
  if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i) collect_pointers(v[i], json_pointer_child(pointer, i), out);
}

struct Outcome {
  int errors = 0;
  bool all_located = true;  // every diagnostic names the file and a line
};

// What `validate` does with one file: best-effort read, then the checks when possible.
Outcome validate_like_the_cli(const std::string& text) {
  Diagnostics diags;
  const auto read = scenario_loading::read_scenario(JsonDocument::parse(text, "s.json"), diags);
  if (read.skeleton_complete) diags.append(check_scenario(read.scenario, tiny_waypoints(), Catalog::embedded()));
  Outcome o;
  o.errors = diags.error_count();
  for (const auto& d : diags.items())
    if (d.where.file != "s.json" || d.where.line <= 0) o.all_located = false;
  return o;
}

}  // namespace

TEST(LoaderRobustness, TheRichScenarioIsValid) {
  const auto o = validate_like_the_cli(rich_scenario());
  EXPECT_EQ(o.errors, 0);
}

TEST(LoaderRobustness, EveryValueReplacedByEveryTypeNeverCrashes) {
  const auto original = nlohmann::json::parse(rich_scenario());
  std::vector<std::string> pointers;
  collect_pointers(original, "", pointers);
  ASSERT_GT(pointers.size(), 140u);
  const std::vector<nlohmann::json> replacements = {nullptr, nlohmann::json::array(), nlohmann::json::object(),
                                                    "text", -1.5, true, 1e12};
  int cases_with_errors = 0;
  for (const auto& pointer : pointers) {
    for (const auto& replacement : replacements) {
      auto changed = original;
      changed[nlohmann::json::json_pointer(pointer)] = replacement;
      const std::string text = changed.dump(1);
      Outcome o;
      ASSERT_NO_THROW(o = validate_like_the_cli(text)) << pointer << " = " << replacement.dump();
      EXPECT_TRUE(o.all_located) << pointer << " = " << replacement.dump();
      cases_with_errors += o.errors > 0 ? 1 : 0;
    }
  }
  // Nearly every replacement is wrong somewhere (a string stays valid as a description).
  EXPECT_GT(cases_with_errors, static_cast<int>(pointers.size() * replacements.size() * 8 / 10));
}

TEST(LoaderRobustness, EveryKeyRemovedNeverCrashes) {
  const auto original = nlohmann::json::parse(rich_scenario());
  std::vector<std::string> pointers;
  collect_pointers(original, "", pointers);
  for (const auto& pointer : pointers) {
    if (pointer.empty()) continue;
    auto changed = original;
    const auto at = nlohmann::json::json_pointer(pointer);
    auto& parent = changed[at.parent_pointer()];
    if (parent.is_object()) parent.erase(at.back());
    else parent.erase(static_cast<std::size_t>(std::stoul(at.back())));
    Outcome o;
    ASSERT_NO_THROW(o = validate_like_the_cli(changed.dump(1))) << pointer;
    EXPECT_TRUE(o.all_located) << pointer;
  }
}
