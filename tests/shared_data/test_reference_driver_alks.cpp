// The UN R157 reference driver as the ego of the real ALKS files (../shared/data), both
// formats: the cut-in without collision stays without one, the unavoidable cut-in collides
// with the reference driver too, and a reference run calls that collision unavoidable.
#include <gtest/gtest.h>

#include "support/cli_runner.hpp"

using namespace orch::test;

namespace {

std::string roadeditor(const std::string& name) {
  return std::string(ORCH_SHARED_DATA_DIR) + "/roadeditor/scenarios/" + name + ".json";
}
std::string xosc(const std::string& name) {
  return std::string(ORCH_SHARED_DATA_DIR) + "/openscenario/" + name + ".xosc";
}

// Runs `file` with the reference driver as the ego and checks that it ended without collision.
nlohmann::json expect_r157_without_collision(const std::string& file, const TempDir& out) {
  const auto r = run_cli({"run", file, "--out", out.path().string(), "-q", "--no-report", "--ego-model", "r157"});
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["ego_model"], "r157");
  EXPECT_EQ(result["verdict"], "success") << result["reason"];
  EXPECT_TRUE(result["collision"].is_null()) << result["collision"];
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return result;
}

}  // namespace

TEST(ReferenceDriverAlks, CutInNoCollisionEndsWithoutCollision) {
  TempDir out;
  expect_r157_without_collision(roadeditor("ALKS_Scenario_4.4_1_CutInNoCollision_TEMPLATE"), out);
  // The driver saw the cut-in (its steps are in the run log).
  EXPECT_NE(slurp(out / "run.log").find("r157: cut-in"), std::string::npos);
}

TEST(ReferenceDriverAlks, UnavoidableCutInCollidesWithTheReferenceDriverToo) {
  TempDir out;
  run_cli({"run", roadeditor("ALKS_Scenario_4.4_2_CutInUnavoidableCollision_TEMPLATE"), "--out", out.path().string(),
           "-q", "--no-report", "--ego-model", "r157"});
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["ego_model"], "r157");
  ASSERT_FALSE(result["collision"].is_null()) << result["reason"];
  EXPECT_EQ(result["collision"]["with"], "actor 1");
  EXPECT_GT(result["collision"]["relative_speed"].get<double>(), 0.0);
  EXPECT_EQ(result["verdict"], "failure");
}

TEST(ReferenceDriverAlks, ReferenceRunCallsTheUnavoidableCutInUnavoidable) {
  TempDir out;
  run_cli({"run", roadeditor("ALKS_Scenario_4.4_2_CutInUnavoidableCollision_TEMPLATE"), "--out", out.path().string(),
           "-q", "--no-report", "--reference-run"});
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["ego_model"], "sumo");
  ASSERT_FALSE(result["collision"].is_null());
  ASSERT_FALSE(result["reference_collision"].is_null());
  EXPECT_EQ(result["preventable"], "unavoidable");
  const auto reference = read_json(out / "reference" / "result.json");
  EXPECT_EQ(reference["ego_model"], "r157");
  EXPECT_EQ(reference["seed"], result["seed"]);
  EXPECT_EQ(result["reference_run"]["verdict"], reference["verdict"]);
  EXPECT_TRUE(result["reference_run"]["min_ttc"].is_number());
  EXPECT_TRUE(result["reference_run"]["reference_min_ttc"].is_number());
}

TEST(ReferenceDriverAlks, OpenScenarioCutInNoCollisionEndsWithoutCollision) {
  TempDir out;
  const auto result = expect_r157_without_collision(xosc("alks_scenario_4_4_1_cut_in_no_collision_template"), out);
  EXPECT_TRUE(result["ego_exposure"]["min_gap"].is_number());
}

// The OSC-ALKS cut-in with the ego's controller named R157ReferenceDriver (catalog entry and
// reference renamed): that entity is the ego and the reference driver drives it, no option needed.
TEST(ReferenceDriverAlks, OpenScenarioControllerNamedR157ReferenceDriverDrivesTheEgo) {
  TempDir dir;
  const std::filesystem::path shared = std::string(ORCH_SHARED_DATA_DIR) + "/openscenario";
  std::filesystem::copy(shared / "catalogs", dir / "catalogs", std::filesystem::copy_options::recursive);
  std::filesystem::copy(shared / "road_networks", dir / "road_networks", std::filesystem::copy_options::recursive);
  auto rename = [](std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  };
  const auto catalog = dir / "catalogs" / "controllers" / "controller_catalog.xosc";
  const std::string renamed =
      rename(slurp(catalog), "<Controller name=\"ALKSController\">", "<Controller name=\"R157ReferenceDriver\">");
  std::ofstream(catalog) << renamed;
  const auto scenario = dir.write(
      "cut_in.xosc", rename(slurp(xosc("alks_scenario_4_4_1_cut_in_no_collision_template")),
                            "entryName=\"ALKSController\"", "entryName=\"R157ReferenceDriver\""));
  const auto r = run_cli({"run", scenario.string(), "--out", (dir / "out").string(), "-q", "--no-report"});
  const auto result = read_json(dir / "out" / "result.json");
  EXPECT_EQ(result["ego_model"], "r157");
  EXPECT_EQ(result["verdict"], "success") << result["reason"];
  EXPECT_NE(slurp(dir / "out" / "run.log").find("Ego: driven by the UN R157 reference driver (controller R157ReferenceDriver is a system under test)"), std::string::npos);
  EXPECT_EQ(r.exit_code, 0) << r.output;
}
