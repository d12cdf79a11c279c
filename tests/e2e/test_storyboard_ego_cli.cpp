// The ego rule of OpenSCENARIO runs through the CLI (docs/openscenario.md "The ego"): an
// entity named Ego without a system-under-test controller does what the storyboard says
// unless the user asks for it to be driven, and run.log, result.json and the trace say so;
// and such an ego that does not brake gives the three verdicts of a reference run
// (preventable, unavoidable, no_collision) in one batch (issue 26).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

// Every `driver` the trace gives the entity.
std::set<std::string> drivers_of(const fs::path& trace_file, const std::string& entity) {
  const Trace trace(trace_file);
  std::set<std::string> out;
  for (const auto& row : trace.rows())
    if (row.str("actor_id") == entity) out.insert(row.str("driver"));
  return out;
}

nlohmann::json ego_record(const nlohmann::json& result) {
  for (const auto& a : result["actors"])
    if (a["ego"] == true) return a;
  return nullptr;
}

}  // namespace

// side_approach.xosc's Ego has no controller: scripted by the storyboard, still the ego of the
// report. `--ego Ego` asks for SUMO to drive it; a misspelt --ego names the entities.
TEST(StoryboardEgoCli, AnEgoWithoutAControllerFollowsTheStoryboardUnlessTheUserAsks) {
  const std::string scenario = source_path("scenarios/openscenario/side_approach.xosc");
  TempDir plain, asked, wrong;
  auto r = run_cli({"run", scenario, "--out", plain.path().string(), "-q", "--no-report", "--max-time", "2"});
  ASSERT_NE(r.exit_code, 2) << r.output;
  std::string log = slurp(plain / "run.log");
  EXPECT_NE(log.find("Ego: follows the storyboard (no controller); the ego of metrics and the report because its "
                     "name is Ego"),
            std::string::npos)
      << log;
  EXPECT_EQ(drivers_of(plain / "trace.csv", "Ego"), std::set<std::string>{"script"});
  auto result = read_json(plain / "result.json");
  EXPECT_EQ(result["ego_model"], "storyboard");
  const auto ego = ego_record(result);
  ASSERT_FALSE(ego.is_null()) << result["actors"].dump();
  EXPECT_EQ(ego["sumo_id"], "Ego");
  EXPECT_EQ(ego["description"], "follows the storyboard (no controller)");

  r = run_cli({"run", scenario, "--out", asked.path().string(), "-q", "--no-report", "--max-time", "2", "--ego", "Ego"});
  ASSERT_NE(r.exit_code, 2) << r.output;
  log = slurp(asked / "run.log");
  EXPECT_NE(log.find("Ego: driven by SUMO (--ego Ego)"), std::string::npos) << log;
  EXPECT_EQ(drivers_of(asked / "trace.csv", "Ego"), std::set<std::string>{"sumo"});
  EXPECT_EQ(read_json(asked / "result.json")["ego_model"], "sumo");

  r = run_cli({"run", scenario, "--out", wrong.path().string(), "-q", "--no-report", "--ego", "SideVehicel"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string reason = read_json(wrong / "result.json")["reason"];
  EXPECT_NE(reason.find("--ego SideVehicel: no such entity (did you mean \"SideVehicle\"?); the entities are Ego, "
                        "SideVehicle"),
            std::string::npos)
      << reason;
}

// scenarios/openscenario/nightly/ego_does_not_brake_outcomes.xosc: three parameter sets of an
// ego that never brakes behind a lead car. With --reference-run: the lead drives away
// (no_collision), brakes gently 40 m ahead (the ego hits it, the R157 driver stops:
// preventable), stands 5 m ahead (both hit it: unavoidable).
TEST(StoryboardEgoCli, ABatchOfAnEgoThatDoesNotBrakeGivesAllThreeVerdicts) {
  TempDir dir;
  const auto r = run_cli({"batch", source_path("scenarios/openscenario/nightly/ego_does_not_brake_outcomes.xosc"),
                          "--reference-run", "--jobs", "2", "--out", (dir / "out").string()});
  ASSERT_NE(r.exit_code, 2) << r.output;
  std::multiset<std::string> outcomes;
  int runs = 0;
  for (const auto& run : fs::directory_iterator(dir / "out" / "runs")) {
    ++runs;
    const auto result = read_json(run.path() / "result.json");
    outcomes.insert(result["preventable"].get<std::string>());
    EXPECT_EQ(result["ego_model"], "storyboard") << run.path();
    EXPECT_EQ(drivers_of(run.path() / "trace.csv", "Ego"), std::set<std::string>{"script"}) << run.path();
    // The reference run's ego is the reference driver's, and its log says why.
    const std::string reference_log = slurp(run.path() / "reference" / "run.log");
    EXPECT_NE(reference_log.find("Ego: driven by the UN R157 reference driver (the reference run)"), std::string::npos)
        << reference_log;
    if (result["preventable"] != "no_collision") {
      EXPECT_EQ(result["collision"]["with"], "LeadVehicle") << result.dump(1);
      EXPECT_EQ(result["verdict"], "failure");
    }
  }
  EXPECT_EQ(runs, 3);
  EXPECT_EQ(outcomes, (std::multiset<std::string>{"no_collision", "preventable", "unavoidable"}));
  // The batch's table and report carry them.
  const std::string csv = slurp(dir / "out" / "metrics.csv");
  for (const char* outcome : {",no_collision", ",preventable", ",unavoidable"})
    EXPECT_NE(csv.find(outcome), std::string::npos) << outcome << "\n" << csv;
  const std::string report = slurp(dir / "out" / "report.html");
  for (const char* outcome : {"\"no_collision\"", "\"preventable\"", "\"unavoidable\""})
    EXPECT_NE(report.find(outcome), std::string::npos) << outcome;
}
