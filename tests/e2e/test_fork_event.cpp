// Forking at an event, OpenSCENARIO variations and the search (docs/forking.md): every run of
// a group writes exactly what the same run from t = 0 writes, on both backends (traci does
// not fork: every run from t = 0, and still the same outputs).
//  - `--fork-at scene:N` / `--fork-at ELEMENT`: the checkpoint is the step where the scene is
//    entered (the storyboard element starts), checked against the scenario before any run;
//  - a variation's sets (`batch --fork`) share the steps before their parameters act;
//  - `search` groups the runs of an iteration the same way.
#include <gtest/gtest.h>

#include "e2e/fork_compare.hpp"
#include "support/cli_runner.hpp"

using namespace orch::test;
using orch::test::forking::rerun_alone;
namespace fs = std::filesystem;

namespace {

const std::string kCutIn = "logical_344b1b1a-8831-46a0-a4e1-e7104d3ce4b5.json";
const char* const kLateBrake = "8fcbbaab-a3d0-472b-b3d5-1046910ecff3";
const std::string kLeadBrakeXosc = source_path("scenarios/openscenario/nightly/lead_brake.xosc");

// The nightly examples (not their parameter files) in `dir`, with `backend` in `logical`'s sumo_config.
fs::path nightly_copy(const fs::path& dir, const std::string& logical, const std::string& backend) {
  for (const auto& e : fs::directory_iterator(source_path("scenarios/nightly")))
    if (e.path().filename().string().find("_parameters.json") == std::string::npos)
      fs::copy_file(e.path(), dir / e.path().filename().string());
  auto j = read_json(dir / logical);
  j["sumo_config"]["backend"] = backend;
  std::ofstream(dir / logical) << j.dump(2);
  return dir / logical;
}

// A 2 x 2 variation of the nightly lead brake: the deceleration and when the lead brakes (the
// lead's speed and the gap, which act at t = 0, stay the scenario's).
fs::path small_variation(const fs::path& dir) {
  const fs::path file = dir / "lead_brake_small_variation.xosc";
  std::ofstream(file) << R"(<?xml version="1.0" encoding="utf-8"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-11-27T00:00:00" author="orchestrator" description="2 x 2"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath=")" << kLeadBrakeXosc << R"("/>
    <Deterministic>
      <DeterministicSingleParameterDistribution parameterName="Decel_mps2">
        <DistributionSet><Element value="4"/><Element value="9"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="BrakeTime_s">
        <DistributionSet><Element value="4"/><Element value="6"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
    </Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
)";
  return file;
}

std::vector<nlohmann::json> traces_of(const fs::path& out) {
  std::vector<nlohmann::json> traces;
  for (const auto& e : fs::directory_iterator(out / "executions")) traces.push_back(read_json(e.path()));
  return traces;
}

class ForkEvent : public ::testing::TestWithParam<std::string> {};

}  // namespace

// The cut-in's sets part once the cut-in car has sped up (8.7 to 10 s); asked for scene 1
// (entered when the ego reaches 80 km/h), every set continues in a process of its own from
// the step it is entered, and every run is its run from t = 0.
TEST_P(ForkEvent, ASceneAsTheCheckpoint) {
  const std::string backend = GetParam();
  TempDir dir;
  const fs::path logical = nightly_copy(dir.path(), kCutIn, backend);
  ASSERT_EQ(run_cli({"sample", logical.string(), "--count", "3", "--seed", "1"}).exit_code, 0);
  const fs::path out = dir / "out";
  const auto batch = run_cli({"batch", logical.string(), "--fork-at", "scene:1", "--jobs", "1", "--out", out.string()});
  ASSERT_LE(batch.exit_code, 1) << batch.output;
  EXPECT_EQ(read_json(out / "batch.json")["options"]["fork_at"], "scene:1");
  int runs = 0, forked = 0;
  for (const auto& trace : traces_of(out)) {
    const fs::path run_dir = out / trace["outputs"]["run_dir"].get<std::string>();
    const auto fork = read_json(run_dir / "fork.json");
    const auto result = read_json(run_dir / "result.json");
    ASSERT_GE(result["scenes"].size(), 2u) << result;
    const double entered = result["scenes"][1]["enter_time"].get<double>();
    if (backend == "traci") {
      EXPECT_FALSE(fork["forked"].get<bool>()) << fork;
      EXPECT_TRUE(fork.contains("not_forked")) << fork;
    } else {
      EXPECT_EQ(fork["fork_at_event"], "scene:1") << fork;
      EXPECT_FALSE(fork.contains("warning")) << fork;
      EXPECT_EQ(fork["checkpoint_s"].get<double>(), entered) << fork;
      if (fork["forked"].get<bool>()) {
        EXPECT_EQ(fork["own_from_s"].get<double>(), entered) << fork;
        ++forked;
      }
    }
    EXPECT_EQ(rerun_alone(out, trace, dir / ("forked_" + std::to_string(runs++))), std::vector<std::string>{})
        << run_dir << " (" << backend << ")";
  }
  EXPECT_EQ(runs, 3);
  if (backend == "libsumo") {
    EXPECT_EQ(forked, 2);
  }
}

// An OpenSCENARIO variation's sets share the steps before their parameters act (batch --fork:
// one seed), and continue from the storyboard event that starts the braking with --fork-at.
TEST(BatchForkVariation, AVariationsSetsShareTheirPrefix) {
  TempDir dir;
  const fs::path variation = small_variation(dir.path());
  for (const std::string& fork_at : {std::string(), std::string("LeadBrakeEvent")}) {
    const fs::path out = dir / ("out" + fork_at);
    std::vector<std::string> args{"batch", variation.string(), "--fork", "--jobs", "1", "--out", out.string()};
    if (!fork_at.empty()) args.insert(args.end(), {"--fork-at", fork_at});
    const auto batch = run_cli(args);
    ASSERT_LE(batch.exit_code, 1) << batch.output;
    int runs = 0, forked = 0;
    for (const auto& trace : traces_of(out)) {
      const fs::path run_dir = out / trace["outputs"]["run_dir"].get<std::string>();
      const auto fork = read_json(run_dir / "fork.json");
      EXPECT_EQ(trace["trace"]["seed"], 1) << trace;  // --fork: the variation's first seed
      if (fork["forked"].get<bool>()) {
        // They part where the first of them brakes: 4 s, or 6 s for the sets that brake then.
        EXPECT_GE(fork["own_from_s"].get<double>(), 4.0) << fork;
        ++forked;
      }
      EXPECT_EQ(rerun_alone(out, trace, dir / ("forked_" + fork_at + std::to_string(runs++))), std::vector<std::string>{})
          << run_dir << " " << fork_at;
    }
    EXPECT_EQ(runs, 4);
    EXPECT_EQ(forked, 3) << fork_at;
  }
}

// The search runs an iteration's points as a batch runs its sets: here the grid's four brake
// times (20 to 30 s) in one iteration share their first 20 s, and every run is its run from t = 0.
TEST_P(ForkEvent, TheSearchSharesThePrefixOfAnIteration) {
  const std::string backend = GetParam();
  TempDir dir;
  const fs::path logical = nightly_copy(dir.path(), "logical_" + std::string(kLateBrake) + ".json", backend);
  const fs::path out = dir / "search";
  const auto search = run_cli({"search", logical.string(), "--objective", "min_ttc", "--minimize", "--method", "grid",
                               "--budget", "4", "--jobs", "1", "--set", "lead.decel=8", "--max-time", "40", "--out",
                               out.string()});
  ASSERT_EQ(search.exit_code, 0) << search.output;
  int runs = 0, forked = 0;
  for (const auto& trace : traces_of(out)) {
    const fs::path run_dir = out / trace["outputs"]["run_dir"].get<std::string>();
    const auto fork = read_json(run_dir / "fork.json");
    if (fork["forked"].get<bool>()) {
      EXPECT_GE(fork["own_from_s"].get<double>(), 20.0) << fork;
      ++forked;
    }
    EXPECT_EQ(rerun_alone(out, trace, dir / ("forked_" + std::to_string(runs++))), std::vector<std::string>{})
        << run_dir << " (" << backend << ")";
  }
  EXPECT_EQ(runs, 4);
  EXPECT_EQ(forked, backend == "libsumo" ? 3 : 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, ForkEvent, ::testing::Values("libsumo", "traci"));

// On traci (nothing to fork) the variants of a variation still run, each from t = 0 with its
// own --param values, and write what their runs alone write.
TEST(RunForkParam, OnTraciEveryVariantRunsFromZeroWithItsOwnValues) {
  TempDir dir;
  const auto r = run_cli({"run", kLeadBrakeXosc, "--out", (dir / "a").string(), "-q", "--no-report", "--backend", "traci",
                          "--param", "Decel_mps2=4", "--fork-with", kLeadBrakeXosc, "--fork-out", (dir / "b").string(),
                          "--fork-param", "1:Decel_mps2=9", "--fork-at", "LeadBrakeEvent"});
  ASSERT_LE(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("not forking"), std::string::npos) << r.output;
  for (const auto& [run, decel] : std::vector<std::pair<std::string, std::string>>{{"a", "4"}, {"b", "9"}}) {
    EXPECT_FALSE(read_json(dir / run / "fork.json")["forked"].get<bool>());
    const auto alone = run_cli({"run", kLeadBrakeXosc, "--out", (dir / ("alone_" + run)).string(), "-q", "--no-report",
                                "--backend", "traci", "--param", "Decel_mps2=" + decel});
    ASSERT_LE(alone.exit_code, 1) << alone.output;
    EXPECT_EQ(slurp(dir / run / "trace.csv"), slurp(dir / ("alone_" + run) / "trace.csv")) << run;
    EXPECT_EQ(slurp(dir / run / "metrics.csv"), slurp(dir / ("alone_" + run) / "metrics.csv")) << run;
  }
  EXPECT_NE(slurp(dir / "a" / "trace.csv"), slurp(dir / "b" / "trace.csv"));  // the values did act
}

// An event the scenario does not have is named before any run, with what it has.
TEST(RunForkAtEvent, AnUnknownEventIsNamedBeforeAnyRun) {
  TempDir dir;
  const auto args = [&](const std::string& file, const std::string& event) {
    return std::vector<std::string>{"run", file, "--out", (dir / "a").string(), "-q", "--fork-with", file,
                                    "--fork-out", (dir / "b").string(), "--fork-at", event};
  };
  auto r = run_cli(args(kLeadBrakeXosc, "LeadBrakeEvnt"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-at LeadBrakeEvnt: " + kLeadBrakeXosc + " has no storyboard element named "
                          "LeadBrakeEvnt; its storyboard elements (Story, Act, ManeuverGroup, Maneuver, Event, Action): "
                          "LeadBrakeStory, LeadBrakeAct, LeadGroup, LeadBrakeManeuver, LeadBrakeEvent, LeadBrake "
                          "(did you mean \"LeadBrakeEvent\"?)"),
            std::string::npos)
      << r.output;
  const std::string json = source_path("scenarios/highway_cut_in.json");
  r = run_cli(args(json, "scene:9"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-at scene:9: " + json + " has no scene 9; its scenes: scene:0, scene:1"),
            std::string::npos)
      << r.output;
  r = run_cli(args(json, "scene:one"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("expected scene:N"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "a" / "result.json"));
  EXPECT_FALSE(fs::exists(dir / "b" / "result.json"));
}

// batch --fork-at EVENT: checked against each logical scenario's first set before the batch
// starts (a template's bound scenes, a variation's storyboard): no folder, no run.
TEST(BatchForkAtEvent, AnUnknownEventIsNamedBeforeTheBatchStarts) {
  TempDir dir;
  const fs::path variation = small_variation(dir.path());
  auto r = run_cli({"batch", variation.string(), "--fork-at", "LeadBrakeEvnt", "--out", (dir / "osc").string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-at LeadBrakeEvnt: " + kLeadBrakeXosc + " has no storyboard element named LeadBrakeEvnt"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("(did you mean \"LeadBrakeEvent\"?)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "osc"));
  const fs::path logical = nightly_copy(dir.path(), kCutIn, "libsumo");
  ASSERT_EQ(run_cli({"sample", logical.string(), "--count", "2", "--seed", "1"}).exit_code, 0);
  r = run_cli({"batch", logical.string(), "--fork-at", "scene:9", "--out", (dir / "json").string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-at scene:9: " + (dir / "cut_in.template.json").string() +
                          " has no scene 9; its scenes: scene:0, scene:1, scene:2, scene:3"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "json"));
}

// The runs end (--max-time 2) before the lead brakes (5 s): no checkpoint. The runs are whole
// and exact; the request was not met, so the command says so and exits with 2.
TEST(RunForkAtEvent, AnEventNoVariantReachesIsAnError) {
  TempDir dir;
  const auto r = run_cli({"run", kLeadBrakeXosc, "--out", (dir / "a").string(), "-q", "--no-report", "--max-time", "2",
                          "--fork-with", kLeadBrakeXosc, "--fork-out", (dir / "b").string(), "--fork-param",
                          "1:Decel_mps2=9", "--fork-at", "LeadBrakeEvent"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-at LeadBrakeEvent: no variant reached the event before its run ended"),
            std::string::npos)
      << r.output;
  for (const char* run : {"a", "b"}) {
    EXPECT_TRUE(fs::exists(dir / run / "result.json")) << run;
    const auto fork = read_json(dir / run / "fork.json");
    EXPECT_TRUE(fork["checkpoint_s"].is_null()) << fork;
    EXPECT_NE(fork["warning"].get<std::string>().find("the event did not happen"), std::string::npos) << fork;
  }
  EXPECT_NE(slurp(dir / "b" / "run.log").find("--param Decel_mps2=9"), std::string::npos);
}

TEST(RunForkParam, NeedsAVariantOfThatNumber) {
  TempDir dir;
  auto r = run_cli({"run", kLeadBrakeXosc, "--out", (dir / "a").string(), "-q", "--fork-with", kLeadBrakeXosc,
                    "--fork-out", (dir / "b").string(), "--fork-param", "2:Decel_mps2=9"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-param 2:Decel_mps2=9: expected K:NAME=VALUE with K the number of a --fork-with "
                          "variant (1 to 1)"),
            std::string::npos)
      << r.output;
  r = run_cli({"run", kLeadBrakeXosc, "--out", (dir / "a").string(), "-q", "--fork-param", "1:Decel_mps2=9"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-param: the parameters of a variant"), std::string::npos) << r.output;
}
