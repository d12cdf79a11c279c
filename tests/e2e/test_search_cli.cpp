// `orchestrator search` end to end: real child runs on SUMO (the nightly lead brake logical
// scenario, two searched parameters, short runs), checked through search.json, the batch
// files beside it and a resumed search that must continue exactly where the first stopped.
#include <gtest/gtest.h>

#include "support/cli_runner.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

const std::string kLeadBrake = source_path("scenarios/nightly/logical_9202dd94-2666-4583-a45c-f8396b848ae9.json");

std::vector<std::string> search_args(const fs::path& out, int budget) {
  return {"search", kLeadBrake, "--objective", "min_ttc", "--minimize", "--budget", std::to_string(budget), "--jobs", "2",
          "--seed", "1", "--set", "lead.brake_time=30", "--max-time", "45", "--out", out.string()};
}

std::vector<nlohmann::json> runs_of(const nlohmann::json& search) {
  std::vector<nlohmann::json> runs;
  for (const auto& it : search["iterations"])
    for (const auto& p : it["points"]) runs.push_back(p);
  return runs;
}

}  // namespace

TEST(SearchCli, FalsificationImprovesOnItsInitialDesignAndResumesExactly) {
  TempDir dir;
  const CliResult full = run_cli(search_args(dir / "full", 10));
  ASSERT_EQ(full.exit_code, 0) << full.output;
  const nlohmann::json s = read_json(dir / "full" / "search.json");
  EXPECT_TRUE(s["finished"].get<bool>());
  ASSERT_EQ(s["dimensions"].size(), 2u);
  EXPECT_EQ(s["dimensions"][0]["key"], "lead.decel");
  EXPECT_EQ(s["fixed"]["lead.brake_time"], 30.0);
  const auto runs = runs_of(s);
  ASSERT_EQ(runs.size(), 10u);
  // The initial design, then expected-improvement batches of --jobs points.
  ASSERT_GE(s["iterations"].size(), 2u);
  EXPECT_EQ(s["iterations"][0]["points"][0]["why"], "corner of the box");
  EXPECT_EQ(s["iterations"][1]["points"].size(), 2u);
  EXPECT_EQ(s["iterations"][1]["points"][0]["why"], "expected improvement");
  EXPECT_GT(s["iterations"][1]["points"][0]["acquisition"].get<double>(), 0);
  const double initial_best = s["iterations"][0]["best_so_far"]["objective"].get<double>();
  const double final_best = s["iterations"].back()["best_so_far"]["objective"].get<double>();
  EXPECT_LT(final_best, initial_best);
  // The critical runs, most critical first, each a batch run with its run folder.
  ASSERT_FALSE(s["critical"].empty());
  EXPECT_EQ(s["critical"][0]["objective"].get<double>(), final_best);
  for (const auto& r : runs) {
    EXPECT_TRUE(fs::exists(dir / "full" / r["run_dir"].get<std::string>() / "result.json")) << r;
    EXPECT_TRUE(fs::exists(dir / "full" / "executions" / ("execution_" + r["run_id"].get<std::string>() + ".json")));
  }
  for (const char* f : {"batch.json", "summary.json", "junit.xml", "report.html", "search.html", "search_parameters.json"})
    EXPECT_TRUE(fs::exists(dir / "full" / f)) << f;

  // Stopped after 6 runs, then resumed to 10: the same runs, with the same values.
  const CliResult first = run_cli(search_args(dir / "part", 6));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const CliResult resumed = run_cli({"search", "--resume", (dir / "part").string(), "--budget", "10"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const auto again = runs_of(read_json(dir / "part" / "search.json"));
  ASSERT_EQ(again.size(), runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(again[i]["run_id"], runs[i]["run_id"]) << i;
    EXPECT_EQ(again[i]["values"], runs[i]["values"]) << i;
    EXPECT_EQ(again[i]["objective"], runs[i]["objective"]) << i;
  }
}

TEST(SearchCli, BadInputIsNamedBeforeAnyRun) {
  TempDir dir;
  const auto fails_with = [&](std::vector<std::string> args, const std::string& text) {
    args.insert(args.end(), {"--out", (dir / "out").string()});
    const CliResult r = run_cli(args);
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(text), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out" / "runs")) << r.output;
  };
  fails_with({"search", kLeadBrake, "--objective", "min_tcc", "--minimize", "--budget", "4"},
             "no metric \"min_tcc\" (did you mean \"min_ttc\"?)");
  fails_with({"search", kLeadBrake, "--objective", "min_ttc", "--minimize", "--budget", "4", "--set", "lead.sped=60"},
             "did you mean \"lead.speed\"");
  fails_with({"search", kLeadBrake, "--objective", "min_ttc", "--budget", "4"}, "give --minimize");
  const std::string cut_in = source_path("scenarios/nightly/logical_344b1b1a-8831-46a0-a4e1-e7104d3ce4b5.json");
  fails_with({"search", cut_in, "--boundary", "verdict", "--budget", "4", "--set", "cut_in.decel=2.5..3.5"},
             "none of its choices is in that range");
}
