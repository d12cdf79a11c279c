// The shipped nightly example (scenarios/nightly/): its parameter files are exactly what
// `orchestrator sample` makes from the logical scenarios today, and a batch of a few of its
// sets gives both successes and failures for the cut-in and for the lead vehicle brake.
#include <gtest/gtest.h>

#include "e2e/test_batch_support.hpp"

using namespace orch::test;
using namespace orch::test::batch;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kLogicals{"344b1b1a-8831-46a0-a4e1-e7104d3ce4b5", "9202dd94-2666-4583-a45c-f8396b848ae9"};

// The example without its parameter files.
void copy_example(const TempDir& dir) {
  for (const auto& e : fs::directory_iterator(source_path("scenarios/nightly")))
    if (e.path().filename().string().find("_parameters.json") == std::string::npos)
      fs::copy_file(e.path(), dir / e.path().filename().string());
}

}  // namespace

TEST(BatchNightly, ShippedParameterFilesAreWhatSampleGivesToday) {
  TempDir dir;
  copy_example(dir);
  for (const auto& uuid : kLogicals) {
    const std::string name = "logical_" + uuid + "_parameters.json";
    const auto shipped = read_json(source_path("scenarios/nightly/" + name));
    const int count = static_cast<int>(shipped["parameters"].size());
    ASSERT_GE(count, 40) << name;
    const auto r = run_cli({"sample", (dir / ("logical_" + uuid + ".json")).string(), "--count", std::to_string(count),
                            "--seed", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto fresh = read_json(dir / name);
    ASSERT_EQ(fresh["parameters"].size(), shipped["parameters"].size());
    for (auto it = shipped["parameters"].begin(); it != shipped["parameters"].end(); ++it) {
      ASSERT_TRUE(fresh["parameters"].contains(it.key())) << it.key();
      const auto& f = fresh["parameters"][it.key()];
      EXPECT_EQ(f["seed"], it.value()["seed"]);
      EXPECT_EQ(f["sampled_values"], it.value()["sampled_values"]) << it.key();  // bit for bit
      EXPECT_EQ(f["sumo_config"], it.value()["sumo_config"]);
    }
  }
}

TEST(BatchNightly, ExampleGivesSuccessesAndFailuresForBothLogicalScenarios) {
  TempDir dir;
  copy_example(dir);
  std::vector<std::string> inputs{"batch"};
  for (const auto& uuid : kLogicals) {
    const auto logical = (dir / ("logical_" + uuid + ".json")).string();
    ASSERT_EQ(run_cli({"sample", logical, "--count", "4", "--seed", "1"}).exit_code, 0);
    inputs.push_back(logical);
  }
  inputs.insert(inputs.end(), {"--out", (dir / "out").string(), "--jobs", "2"});
  const auto r = run_cli(inputs);
  EXPECT_EQ(r.exit_code, 1) << r.output;  // failures by design, no errors
  const auto summary = read_json(dir / "out" / "summary.json");
  ASSERT_EQ(summary["logical_scenarios"].size(), 2u);
  for (const auto& l : summary["logical_scenarios"]) {
    EXPECT_GE(l["success"].get<int>(), 1) << l.dump();
    EXPECT_GE(l["failure"].get<int>(), 1) << l.dump();
    EXPECT_EQ(l["error"], 0) << l.dump();
  }
  // Failures say why in the scenario's own terms: a collision, or closing in too fast.
  for (const auto& run : summary["runs"]) {
    if (run["verdict"] != "failure") continue;
    const std::string reason = run["reason"];
    EXPECT_TRUE(reason.find("collided") != std::string::npos || reason.find("relative speed") != std::string::npos)
        << reason;
  }
}
