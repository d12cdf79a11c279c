// The 13 real ScenarioExecutor files in ../shared/data: every one loads and checks with no
// error, the known warnings are there, and the model holds what the files say.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "map/waypoint_file.hpp"
#include "scenario_executor/catalog.hpp"
#include "scenario_executor/loader.hpp"
#include "scenario_executor/validator.hpp"
#include "support/cli_runner.hpp"

namespace fs = std::filesystem;
using namespace orch;
using namespace orch::scenario;

namespace {

const fs::path kRoadEditor = fs::path(ORCH_SHARED_DATA_DIR) / "roadeditor";

// map_id -> waypoint file, as in ../shared/data/roadeditor/README.md
const std::map<std::string, std::string> kWaypointFileOfMap = {
    {"highway", "highway.waypoint.json"},
    {"ALKS_Road", "ALKS.Road.waypoint.json"},
    {"ALKS_Road_Different_Curvatures", "ALKS.Road.Curvatures.waypoint.json"}};

const WaypointFile& waypoints_for(const std::string& map_id) {
  static std::map<std::string, std::unique_ptr<WaypointFile>> cache;
  auto& slot = cache[map_id];
  if (!slot)
    slot = std::make_unique<WaypointFile>(
        load_waypoint_file((kRoadEditor / "waypoints" / kWaypointFileOfMap.at(map_id)).string()));
  return *slot;
}

std::string scenario_path(const std::string& name) { return (kRoadEditor / "scenarios" / name).string(); }

struct Checked {
  Scenario scenario;
  Diagnostics diagnostics;  // loader and check_scenario together
};

Checked load_and_check(const std::string& name, ValidationOptions options = {}) {
  auto loaded = load_scenario(scenario_path(name));
  EXPECT_FALSE(loaded.diagnostics.has_errors()) << loaded.diagnostics.format();
  if (!loaded.scenario) return {};
  Checked out{*loaded.scenario, loaded.diagnostics};
  out.diagnostics.append(
      check_scenario(*loaded.scenario, waypoints_for(loaded.scenario->map_id), Catalog::embedded(), options));
  return out;
}

const Diagnostic* find_diagnostic(const Diagnostics& d, Severity severity, const std::string& pointer,
                                  const std::string& text) {
  for (const auto& item : d.items())
    if (item.severity == severity && item.where.pointer == pointer && item.message.find(text) != std::string::npos)
      return &item;
  return nullptr;
}

std::vector<std::string> all_scenario_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kRoadEditor / "scenarios"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST(SharedScenarios, AllThirteenLoadAndCheckWithoutErrors) {
  const auto names = all_scenario_files();
  ASSERT_EQ(names.size(), 13u);
  for (const auto& name : names) {
    SCOPED_TRACE(name);
    const Checked c = load_and_check(name);
    EXPECT_EQ(c.diagnostics.error_count(), 0) << c.diagnostics.format();
    EXPECT_EQ(c.scenario.file, scenario_path(name));
    EXPECT_TRUE(kWaypointFileOfMap.count(c.scenario.map_id)) << c.scenario.map_id;
  }
}

TEST(SharedScenarios, TargetPastTheShorterCurvedRouteIsAWarningNamingFileLineAndPointer) {
  const std::string name = "ALKS_Scenario_4.1_1_FreeDriving_TEMPLATE.json";
  const Checked c = load_and_check(name);
  // The ALKS template was copied to the 5101-point curved road but still aims at 10000.
  const auto* end = find_diagnostic(c.diagnostics, Severity::Warning, "/scenario/opening_scene/ego/end_position",
                                    "wp_idx 10000 is past the end of route \"Waypoint02\" (last index 5100)");
  ASSERT_NE(end, nullptr) << c.diagnostics.format();
  EXPECT_EQ(end->where.line, 19);
  EXPECT_EQ(end->where.file, scenario_path(name));
  const auto* goal = find_diagnostic(c.diagnostics, Severity::Warning,
                                     "/scenario/ending_scenes/0/conditions/or/0/position", "wp_idx 10000");
  ASSERT_NE(goal, nullptr) << c.diagnostics.format();
  EXPECT_EQ(goal->where.line, 60);
  // The `{}` action is accepted with a warning.
  EXPECT_NE(find_diagnostic(c.diagnostics, Severity::Warning, "/scenario/scenes/0/actions/0", "empty action"),
            nullptr);
  EXPECT_EQ(c.diagnostics.warning_count(), 3) << c.diagnostics.format();
}

TEST(SharedScenarios, StrictTurnsTheTargetPastTheRouteIntoAnError) {
  ValidationOptions strict;
  strict.strict = true;
  const Checked c = load_and_check("ALKS_Scenario_4.1_1_FreeDriving_TEMPLATE.json", strict);
  EXPECT_EQ(c.diagnostics.error_count(), 2) << c.diagnostics.format();
  EXPECT_NE(find_diagnostic(c.diagnostics, Severity::Error, "/scenario/opening_scene/ego/end_position", "strict"),
            nullptr);
}

TEST(SharedScenarios, TenThousandIsTheLastPointOfTheStraightAlksRoad) {
  // ALKS_Road routes have 10001 points: wp_idx 10000 is on the route, so no warning.
  const Checked c = load_and_check("ALKS_Scenario_4.2_1_FullyBlockingTarget_TEMPLATE.json");
  EXPECT_EQ(c.diagnostics.warning_count(), 0) << c.diagnostics.format();
}

TEST(SharedScenarios, HighwayCutinHasFiveScenesOneEndingAndWarnsAboutItsEndPosition) {
  const Checked c = load_and_check("highway_cutin.json");
  const auto& s = c.scenario;
  EXPECT_EQ(s.map_id, "highway");
  const auto endings = std::count_if(s.scenes.begin(), s.scenes.end(), [](const Scene& x) { return x.ending; });
  EXPECT_EQ(s.scenes.size() - static_cast<std::size_t>(endings), 5u);
  EXPECT_EQ(endings, 1);
  ASSERT_NE(s.find_scene(6), nullptr);
  EXPECT_TRUE(s.find_scene(6)->ending);
  EXPECT_EQ(s.opening.next_scenes, std::vector<SceneId>{1});
  EXPECT_DOUBLE_EQ(s.find_scene(3)->duration, 3.0);
  EXPECT_EQ(s.ego.model_id, "vehicle.bmw.grandtourer");
  EXPECT_EQ(s.others.at(0).color, "ff0000");

  // Scene 1: or(position reach, simulation_time >= 180); speed 95 km/h with accel 1 m/s^2.
  const Scene& first = *s.find_scene(1);
  EXPECT_EQ(first.conditions.logic, Logic::Or);
  ASSERT_EQ(first.conditions.items.size(), 2u);
  const auto& reach = std::get<PositionCondition>(std::get<Condition>(first.conditions.items[0].node).kind);
  EXPECT_EQ(reach.waypoint.wp_id, "Waypoint01");
  EXPECT_DOUBLE_EQ(reach.waypoint.wp_idx, 810);
  EXPECT_DOUBLE_EQ(reach.tolerance, 2);
  const auto& speed = std::get<SpeedAction>(first.actions.at(0).kind);
  EXPECT_NEAR(speed.value, 95 / 3.6, 1e-12);
  EXPECT_EQ(speed.accel.type, AccelType::Specify);
  EXPECT_DOUBLE_EQ(speed.accel.value, 1);

  // Scene 4 has no conditions object: always true.
  EXPECT_TRUE(s.find_scene(4)->conditions.items.empty());
  EXPECT_EQ(std::get<LaneChangeAction>(s.find_scene(4)->actions.at(0).kind).wp_id, "Waypoint02");

  // Opening: actor 1 starts with the ego's speed (relative 0 to actor 0).
  const auto& start_speed = s.opening.others.at(0).start_speed;
  ASSERT_TRUE(start_speed.has_value());
  EXPECT_EQ(start_speed->type, SpeedType::Relative);
  EXPECT_EQ(start_speed->target, std::optional<ActorId>(0));
  EXPECT_EQ(start_speed->actor, 1);

  // 1940-point routes: end_position 10000 is past the end.
  EXPECT_NE(find_diagnostic(c.diagnostics, Severity::Warning, "/scenario/opening_scene/ego/end_position",
                            "(last index 1939)"),
            nullptr)
      << c.diagnostics.format();
  EXPECT_EQ(c.diagnostics.warning_count(), 1) << c.diagnostics.format();
}

TEST(SharedScenarios, FullyBlockingTargetIsAPedestrianModel) {
  const Checked c = load_and_check("ALKS_Scenario_4.2_1_FullyBlockingTarget_TEMPLATE.json");
  const ActorSpec* target = c.scenario.find_actor(1);
  ASSERT_NE(target, nullptr);
  EXPECT_EQ(target->model_id, "walker.pedestrian.0001");
  EXPECT_EQ(target->description, "TargetBlocking");
  const Catalog catalog = Catalog::embedded();
  const ModelInfo* model = catalog.find(target->model_id);
  ASSERT_NE(model, nullptr);
  EXPECT_EQ(model->kind, ActorKind::Pedestrian);
  EXPECT_EQ(model->id, "walker.pedestrian.*");
  EXPECT_EQ(c.scenario.title, "ALKS_Scenario_4.2_1_FullyBlockingTarget_TEMPLATE");
  EXPECT_EQ(c.scenario.description, "ALKS Scenario 4.2_1 FullyBlockingTarget Template");
}

TEST(SharedScenarios, SwervingLeadVehicleKeepsItsFractionalIndexAndDefaultsToGodsHand) {
  const Checked c = load_and_check("ALKS_Scenario_4.1_2_SwervingLeadVehicle_TEMPLATE.json");
  const auto& lead = c.scenario.opening.others.at(0);
  ASSERT_TRUE(lead.start.waypoint.has_value());
  EXPECT_DOUBLE_EQ(lead.start.waypoint->wp_idx, 33.33333333);
  EXPECT_EQ(lead.description, "LeadVehicle");
  // Scene 1's speed action names no accel: the speed is set at once ("gods_hand").
  const auto& set_speed = std::get<SpeedAction>(c.scenario.find_scene(1)->actions.at(0).kind);
  EXPECT_EQ(set_speed.accel.type, AccelType::GodsHand);
  EXPECT_EQ(c.scenario.find_scene(1)->actions.at(0).description, "set LeadVehicle speed 60kmph");
  EXPECT_EQ(std::get<Condition>(c.scenario.find_scene(1)->conditions.items.at(0).node).description,
            "ego speed >= 60kmph");
  // Scene 3: `"conditions": {}` is always true; route_move of type wp_offset with six legs.
  const Scene& swerve = *c.scenario.find_scene(3);
  EXPECT_TRUE(swerve.conditions.items.empty());
  const auto& move = std::get<RouteMoveAction>(swerve.actions.at(0).kind);
  EXPECT_EQ(move.type, RouteMoveType::WpOffset);
  ASSERT_EQ(move.legs.size(), 6u);
  EXPECT_DOUBLE_EQ(move.legs[3].wp_offset.value(), -1.0);
  EXPECT_DOUBLE_EQ(move.legs[1].time, 5);
  EXPECT_DOUBLE_EQ(c.scenario.find_scene(2)->duration, 5.0);
}

TEST(SharedScenarios, CutOutDistanceConditionUsesTheDocumentedDefaults) {
  const Checked c = load_and_check("ALKS_Scenario_4.5_1_CutOutFullyBlocking_TEMPLATE.json");
  const auto& cond = std::get<DistanceCondition>(
      std::get<Condition>(c.scenario.find_scene(2)->conditions.items.at(0).node).kind);
  EXPECT_EQ(cond.actor, 1);
  EXPECT_EQ(cond.target, 2);
  EXPECT_EQ(cond.type, DistanceType::Traveled);
  EXPECT_EQ(cond.measure, MeasureType::Center);
  EXPECT_EQ(cond.comparison, Comparison::Less);
  EXPECT_DOUBLE_EQ(cond.value, 50);
}

TEST(SharedScenarios, ForwardDetectionRangeHasNoScenesAndAnOffsetTarget) {
  const Checked c = load_and_check("ALKS_Scenario_4.6_1_ForwardDetectionRange_TEMPLATE.json");
  ASSERT_EQ(c.scenario.scenes.size(), 1u);
  EXPECT_TRUE(c.scenario.scenes[0].ending);
  EXPECT_DOUBLE_EQ(c.scenario.opening.others.at(0).start.wp_offset, -5.25);
  ASSERT_TRUE(c.scenario.stop_conditions.has_value());
  const auto& stop = std::get<SimulationTimeCondition>(
      std::get<Condition>(c.scenario.stop_conditions->items.at(0).node).kind);
  EXPECT_EQ(stop.comparison, Comparison::Greater);
  EXPECT_DOUBLE_EQ(stop.value, 3600);
}

TEST(SharedScenarios, FreeDrivingHasNoOtherActors) {
  const Checked c = load_and_check("ALKS_Scenario_4.1_1_FreeDriving_TEMPLATE.json");
  EXPECT_TRUE(c.scenario.others.empty());
  EXPECT_TRUE(c.scenario.opening.others.empty());
  EXPECT_TRUE(std::holds_alternative<EmptyAction>(c.scenario.find_scene(1)->actions.at(0).kind));
}

// The binary on all 13 files, with a map folder per map_id pointing at the shared
// waypoint files, so that this does not depend on the maps built under sumo_nets/.
TEST(SharedScenarios, ValidateCommandAcceptsAllThirteen) {
  const orch::test::TempDir maps;
  for (const auto& [map_id, file] : kWaypointFileOfMap) {
    fs::create_directories(maps / map_id);
    maps.write(map_id + "/map.json", "{\"id\": \"" + map_id + "\", \"waypoint_file\": \"" +
                                         (kRoadEditor / "waypoints" / file).string() +
                                         "\", \"net_file\": \"net.net.xml\"}\n");
  }
  std::vector<std::string> args{"validate"};
  for (const auto& name : all_scenario_files()) args.push_back(scenario_path(name));
  args.insert(args.end(), {"--maps", maps.path().string()});  // last: --maps takes every value after it
  const auto result = orch::test::run_cli(args);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("13 files checked: 13 valid, 0 invalid"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find(scenario_path("ALKS_Scenario_4.1_1_FreeDriving_TEMPLATE.json") +
                               ":19: warning: /scenario/opening_scene/ego/end_position: wp_idx 10000 is past the "
                               "end of route \"Waypoint02\" (last index 5100)"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find(": error: "), std::string::npos) << result.output;
}
