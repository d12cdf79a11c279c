// Property: whatever is done to a real scenario file -- a value replaced, a key removed, a
// list item duplicated, bytes overwritten, a number made extreme but still valid (0,
// negative, x10^6, x10^-3) -- `orchestrator run` exits 0, 1 or 2, writes a parseable
// result.json whose verdict matches the exit status, and leaves no process behind.
// A fixed list of seeds (support/mutation.hpp); ORCH_PROPERTY_SEED / ORCH_PROPERTY_RUNS
// replay or extend (scripts/soak.sh draws random seeds).
#include <gtest/gtest.h>

#include "e2e/mutated_run_check.hpp"

using namespace orch::test;

namespace {

std::vector<std::filesystem::path> real_scenarios() {
  std::vector<std::filesystem::path> files;
  for (const auto& dir : {source_path("scenarios"), std::string(ORCH_SHARED_DATA_DIR) + "/roadeditor/scenarios"}) {
    if (!std::filesystem::is_directory(dir)) continue;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST(MutatedScenariosCli, EveryMutationEndsInAWrittenResult) {
  // 249426645 found issue 22 (with ../shared present); 20261126 is the day it was fixed.
  // Short runs: the property is about the ending, not about the whole scenario.
  check_mutants("json", real_scenarios(), property_seeds({249426645, 20261126}, 16), {"--max-time", "20"},
                [](const std::filesystem::path& source, std::mt19937_64& rng, const std::string& stem) {
                  Mutation m = mutate_json(slurp(source), rng);
                  const std::filesystem::path file = stem + ".json";
                  std::ofstream(file) << m.text;
                  return WrittenMutant{std::move(m), file, source};
                });
}

// Mutants that once failed, kept as files: each must now be refused by `validate` with the
// key named, and `run` must end in a written result.json (exit 2, bad input).
TEST(MutatedScenariosCli, KeptRegressionsAreRefusedWithTheKeyNamed) {
  const auto dir = std::filesystem::path(source_path("tests/data/regressions/mutants"));
  int seen = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".json") continue;
    ++seen;
    SCOPED_TRACE(e.path().filename().string());
    const auto expected = slurp(std::filesystem::path(e.path()).replace_extension(".expected"));
    const auto v = run_cli({"validate", e.path().string()});
    EXPECT_EQ(v.exit_code, 1) << v.output;
    EXPECT_NE(v.output.find(expected.substr(0, expected.find('\n'))), std::string::npos) << v.output;
    TempDir out;
    const auto r = run_scenario(e.path().string(), out, {"--max-time", "20"});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    ASSERT_TRUE(std::filesystem::exists(out / "result.json")) << r.output;
    EXPECT_EQ(read_json(out / "result.json")["verdict"], "error");
  }
  EXPECT_GE(seen, 1);
}
