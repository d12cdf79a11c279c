// Forking (docs/forking.md): every run of a forked batch over the shipped nightly examples
// writes exactly what the same run from t = 0 writes (wall-clock fields aside, as
// scripts/same_outputs/compare.py compares), on both backends (traci does not fork: it says
// so and runs every set from t = 0).
#include <gtest/gtest.h>

#include "e2e/fork_compare.hpp"
#include "e2e/test_batch_support.hpp"

using namespace orch::test;
using orch::test::forking::rerun_alone;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kNightly{"344b1b1a-8831-46a0-a4e1-e7104d3ce4b5", "4aae47a9-c775-4dd8-9373-02c03b91dd6b",
                                        "9202dd94-2666-4583-a45c-f8396b848ae9", "8fcbbaab-a3d0-472b-b3d5-1046910ecff3"};
const std::string kLateBrake = "8fcbbaab-a3d0-472b-b3d5-1046910ecff3";

class BatchFork : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(BatchFork, EveryForkedRunWritesWhatTheRunFromZeroWrites) {
  const std::string backend = GetParam();
  TempDir dir;
  for (const auto& e : fs::directory_iterator(source_path("scenarios/nightly")))
    if (e.path().filename().string().find("_parameters.json") == std::string::npos)
      fs::copy_file(e.path(), dir / e.path().filename().string());
  std::vector<std::string> args{"batch"};
  for (const auto& uuid : kNightly) {
    const fs::path logical = dir / ("logical_" + uuid + ".json");
    auto j = read_json(logical);
    j["sumo_config"]["backend"] = backend;
    std::ofstream(logical) << j.dump(2);
    ASSERT_EQ(run_cli({"sample", logical.string(), "--count", "3", "--seed", "1"}).exit_code, 0);
    args.push_back(logical.string());
  }
  const fs::path out = dir / "out";
  args.insert(args.end(), {"--fork", "--out", out.string(), "--jobs", "2"});
  const auto batch = run_cli(args);
  ASSERT_LE(batch.exit_code, 1) << batch.output;  // failures by design, no errors

  double saved_late_brake = 0;
  int runs = 0;
  for (const auto& e : fs::directory_iterator(out / "executions")) {
    const auto trace = read_json(e.path());
    const fs::path run_dir = out / trace["outputs"]["run_dir"].get<std::string>();
    const auto fork = read_json(run_dir / "fork.json");
    if (backend == "traci") {
      EXPECT_FALSE(fork["forked"].get<bool>()) << run_dir;
      EXPECT_NE(slurp(run_dir / "child.log").find("not forking"), std::string::npos) << run_dir;
    }
    if (trace["logical_uuid"] == kLateBrake) saved_late_brake += fork["saved_s"].get<double>();
    EXPECT_EQ(trace["trace"]["implementation"]["fork"], fork) << e.path();  // the execution trace says it too
    // The same run from t = 0: its own command without the other variants.
    EXPECT_EQ(rerun_alone(out, trace, dir / ("forked_" + std::to_string(runs++))), std::vector<std::string>{})
        << run_dir << " (" << backend << ")";
  }
  EXPECT_EQ(runs, 12);
  // The late brake's sets share at least their first 20 s (libsumo): two of three forked.
  if (backend == "libsumo") {
    EXPECT_GE(saved_late_brake, 40.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, BatchFork, ::testing::Values("libsumo", "traci"));

TEST(RunForkWith, RefusesUnpairedVariantsAndViewers) {
  TempDir dir;
  const std::string scenario = source_path("scenarios/highway_cut_in.json");
  auto r = run_cli({"run", scenario, "--out", (dir / "a").string(), "-q", "--fork-with", scenario});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-with and --fork-out come in pairs: 1 --fork-with, 0 --fork-out"), std::string::npos)
      << r.output;
  r = run_cli({"run", scenario, "--out", (dir / "a").string(), "-q", "--fork-with", scenario, "--fork-out",
               (dir / "b").string(), "--realtime", "100"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-with runs variants without a viewer"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "b" / "result.json"));
}

// Two copies of one scenario give the same commands at every step: they share the whole run
// (the copy is never forked) and both folders hold the run.
TEST(RunForkWith, EqualVariantsShareEveryStep) {
  TempDir dir;
  const std::string scenario = source_path("scenarios/highway_cut_in.json");
  const auto r = run_cli({"run", scenario, "--out", (dir / "a").string(), "-q", "--no-report", "--fork-with", scenario,
                          "--fork-out", (dir / "b").string()});
  ASSERT_LE(r.exit_code, 1) << r.output;
  EXPECT_FALSE(read_json(dir / "b" / "fork.json")["forked"].get<bool>());
  EXPECT_EQ(read_json(dir / "a" / "fork.json")["process"], read_json(dir / "b" / "fork.json")["process"]);
  EXPECT_EQ(slurp(dir / "a" / "trace.csv"), slurp(dir / "b" / "trace.csv"));
}

// --fork-at: a checkpoint by request. The late brake's sets part at 20 to 30 s; asked for 10 s,
// every set continues in a process of its own from 10 s. The lead brake's sets part at t = 0
// (the lead's speed): they still part there, exactly, and fork.json warns. Either way every
// run writes what the run from t = 0 writes.
TEST(BatchForkAt, ForksAtTheRequestedTimeAndWarnsWhereTheVariantsPartEarlier) {
  TempDir dir;
  const std::string late = "logical_" + kLateBrake + ".json", early = "logical_9202dd94-2666-4583-a45c-f8396b848ae9.json";
  for (const auto& e : fs::directory_iterator(source_path("scenarios/nightly")))
    if (e.path().filename().string().find("_parameters.json") == std::string::npos)
      fs::copy_file(e.path(), dir / e.path().filename().string());
  std::vector<std::string> args{"batch"};
  for (const auto& name : {late, early}) {
    ASSERT_EQ(run_cli({"sample", (dir / name).string(), "--count", "3", "--seed", "1"}).exit_code, 0);
    args.push_back((dir / name).string());
  }
  const fs::path out = dir / "out";
  args.insert(args.end(), {"--fork-at", "10", "--out", out.string(), "--jobs", "2"});
  const auto batch = run_cli(args);
  ASSERT_LE(batch.exit_code, 1) << batch.output;
  EXPECT_EQ(read_json(out / "batch.json")["options"]["fork_at"], 10.0);
  int runs = 0, forked_at_checkpoint = 0, warned = 0;
  for (const auto& e : fs::directory_iterator(out / "executions")) {
    const auto trace = read_json(e.path());
    const fs::path run_dir = out / trace["outputs"]["run_dir"].get<std::string>();
    const auto fork = read_json(run_dir / "fork.json");
    EXPECT_EQ(fork["fork_at_s"], 10.0) << run_dir;
    if (trace["logical_uuid"] == kLateBrake) {
      EXPECT_FALSE(fork.contains("warning")) << fork;
      if (fork["forked"].get<bool>()) {
        EXPECT_GE(fork["own_from_s"].get<double>(), 10.0) << fork;
        EXPECT_LT(fork["own_from_s"].get<double>(), 10.5) << fork;  // not at 20 s, where they part
        ++forked_at_checkpoint;
      }
    } else {
      ASSERT_TRUE(fork.contains("warning")) << fork;
      EXPECT_NE(fork["warning"].get<std::string>().find("before the requested time"), std::string::npos) << fork;
      EXPECT_LT(fork["own_from_s"].get<double>(), 10.0) << fork;
      ++warned;
    }
    EXPECT_EQ(rerun_alone(out, trace, dir / ("forked_" + std::to_string(runs++))), std::vector<std::string>{}) << run_dir;
  }
  EXPECT_EQ(runs, 6);
  EXPECT_EQ(forked_at_checkpoint, 2);
  EXPECT_EQ(warned, 3);
}

TEST(RunForkAt, NeedsVariants) {
  TempDir dir;
  const auto r = run_cli({"run", source_path("scenarios/highway_cut_in.json"), "--out", (dir / "a").string(), "-q",
                          "--fork-at", "5"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--fork-at: a checkpoint for variants"), std::string::npos) << r.output;
}
