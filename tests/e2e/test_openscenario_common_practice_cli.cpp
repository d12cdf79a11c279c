// tests/data/openscenario/'s files of common practice through the real CLI on SUMO: the
// actors a ManeuverGroup selects by the Act's triggering entities, the actions that run with
// no effect on motion (warned in run.log and result.json).
#include <gtest/gtest.h>

#include <map>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kData = std::string(ORCH_SOURCE_DIR) + "/tests/data/openscenario/";

// Each actor's last trace row's `column`.
std::map<std::string, double> last(const Trace& trace, const std::string& column) {
  std::map<std::string, double> out;
  for (const auto& row : trace.rows()) out[row.str("actor_id")] = row.num(column);
  return out;
}

TEST(OpenScenarioCommonPracticeCli, TriggeringEntitiesActAndNoEffectActionsAreRecorded) {
  TempDir out;
  const auto r = run_cli({"run", kData + "common_practice.xosc", "--out", out.path().string(), "-q"});
  const auto result = read_json(out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  std::string warnings;
  for (const auto& w : result["warnings"]) warnings += w.get<std::string>() + "\n";
  for (const char* what : {"followingMode=\"follow\"", "CustomCommandAction type=\"python\"",
                           "OverrideControllerValueAction runs with no effect", "AnimationAction runs with no effect",
                           "activateLighting=\"true\""})
    EXPECT_NE(warnings.find(what), std::string::npos) << what << "\n" << warnings;
  const std::string log = slurp(out / "run.log");
  EXPECT_NE(log.find("CustomCommandAction type=\"log\""), std::string::npos) << log;
  for (const char* action : {"BrakeOverride", "MirrorFold", "Notify"})
    EXPECT_NE(log.find(std::string("action ") + action + " endTransition"), std::string::npos) << action << "\n" << log;
  // On SUMO: Ego, which triggered the Act, slowed to Lead's speed; Other did not.
  const Trace trace(out / "trace.csv");
  const auto speed = last(trace, "speed");
  EXPECT_NEAR(speed.at("Ego"), 10.0, 0.01);
  EXPECT_NEAR(speed.at("Other"), 15.0, 0.01);
}

}  // namespace
