// The eight OSC-ALKS scenarios (../shared/data/openscenario) load with no error, and the
// model holds what the files say once parameters are substituted.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/errors.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"

namespace {

using namespace orch::openscenario;

std::string alks(const std::string& name) {
  return std::string(ORCH_SHARED_DATA_DIR) + "/openscenario/" + name + ".xosc";
}

TEST(OpenScenarioAlksFiles, AllEightLoad) {
  int loaded = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(ORCH_SHARED_DATA_DIR) + "/openscenario")) {
    if (entry.path().extension() != ".xosc") continue;
    SCOPED_TRACE(entry.path().string());
    const Scenario s = load_scenario(entry.path().string());
    EXPECT_EQ(s.rev_major, 1);
    EXPECT_EQ(s.rev_minor, 1);
    ASSERT_NE(s.entity("Ego"), nullptr);
    ASSERT_TRUE(s.entity("Ego")->controller.has_value());
    EXPECT_EQ(s.entity("Ego")->controller->name, "ALKSController");
    EXPECT_TRUE(std::filesystem::exists(s.road_file));
    EXPECT_TRUE(s.storyboard.stop_trigger.has_value());
    ++loaded;
  }
  EXPECT_EQ(loaded, 8);
}

TEST(OpenScenarioAlksFiles, CutInPositionsComeFromTheParameterExpressions) {
  const Scenario s = load_scenario(alks("alks_scenario_4_4_1_cut_in_no_collision_template"));
  const InitAction* cut_in = nullptr;
  for (const InitAction& a : s.storyboard.init)
    if (a.entity == "CutInVehicle" && std::holds_alternative<TeleportAction>(a.action)) cut_in = &a;
  ASSERT_NE(cut_in, nullptr);
  const auto& p = std::get<RelativeLanePosition>(std::get<TeleportAction>(cut_in->action).position);
  EXPECT_EQ(p.entity, "Ego");
  EXPECT_EQ(p.d_lane, -1);
  // ds = dx0 + (-10 * (Vrel / 3.6)) with dx0 = 30, Vrel = -20 km/h.
  EXPECT_NEAR(p.ds, 30.0 + 10.0 * 20.0 / 3.6, 1e-9);
  const Entity& ego = *s.entity("Ego");
  EXPECT_DOUBLE_EQ(ego.box.center_x, 1.4);  // reference point: rear axle, box centre 1.4 m ahead
  EXPECT_DOUBLE_EQ(ego.rear_axle->position_x, 0.0);
}

TEST(OpenScenarioAlksFiles, ParamOverrideReachesTheModelAndConstraintsHold) {
  LoadOptions options;
  options.parameter_overrides["Ego_InitSpeed_Ve0_kph"] = "36";
  const Scenario s = load_scenario(alks("alks_scenario_4_4_1_cut_in_no_collision_template"), options);
  const auto& speed = std::get<SpeedAction>(s.storyboard.init.at(1).action);
  EXPECT_NEAR(std::get<AbsoluteTargetSpeed>(speed.target).value, 10.0, 1e-12);
  options.parameter_overrides["Ego_InitSpeed_Ve0_kph"] = "70";  // the file allows up to 60
  EXPECT_THROW((void)load_scenario(alks("alks_scenario_4_4_1_cut_in_no_collision_template"), options),
               orch::ScenarioError);
}

TEST(OpenScenarioAlksFiles, CliValidateChoosesTheFormatByContent) {
  std::vector<std::string> args = {"validate"};
  for (const auto& entry : std::filesystem::directory_iterator(std::string(ORCH_SHARED_DATA_DIR) + "/openscenario"))
    if (entry.path().extension() == ".xosc") args.push_back(entry.path().string());
  const auto all = orch::test::run_cli(args);
  EXPECT_EQ(all.exit_code, 0) << all.output;
  EXPECT_NE(all.output.find("8 files checked: 8 valid, 0 invalid"), std::string::npos) << all.output;

  const std::string cut_in = alks("alks_scenario_4_4_1_cut_in_no_collision_template");
  const auto violated = orch::test::run_cli({"validate", "--param", "Ego_InitSpeed_Ve0_kph=70", cut_in});
  EXPECT_EQ(violated.exit_code, 1) << violated.output;
  EXPECT_NE(violated.output.find(":9: error: /OpenSCENARIO/ParameterDeclarations/ParameterDeclaration[1]/@value: "
                                 "parameter \"Ego_InitSpeed_Ve0_kph\" = 70 violates its constraints"),
            std::string::npos)
      << violated.output;
  const auto malformed = orch::test::run_cli({"validate", "--param", "Ego_InitSpeed_Ve0_kph", cut_in});
  EXPECT_EQ(malformed.exit_code, 2) << malformed.output;
  EXPECT_NE(malformed.output.find("expected NAME=VALUE"), std::string::npos) << malformed.output;
}

}  // namespace
