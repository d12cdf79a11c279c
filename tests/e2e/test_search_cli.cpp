// `orchestrator search` end to end: real child runs on SUMO (the nightly lead brake logical
// scenario, two searched parameters, short runs), checked through search.json, the batch
// files beside it and a resumed search that must continue exactly where the first stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>

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
  // The initial design, then batches of --jobs points: a poll around the best corner (both of
  // its directions along the box's faces), then expected improvement.
  ASSERT_GE(s["iterations"].size(), 3u);
  EXPECT_EQ(s["iterations"][0]["points"][0]["why"], "corner of the box");
  EXPECT_EQ(s["iterations"][1]["points"].size(), 2u);
  for (const auto& p : s["iterations"][1]["points"]) {
    EXPECT_EQ(p["why"], "pattern search around the best");
    EXPECT_EQ(p["acquisition"].get<double>(), 0.25);  // the poll's first step
  }
  EXPECT_EQ(s["iterations"][2]["points"][0]["why"], "expected improvement");
  EXPECT_GT(s["iterations"][2]["points"][0]["acquisition"].get<double>(), 0);
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
  // The page: axes with units, the most critical run ringed, runs numbered (not by their
  // shortened ids, which all begin with the logical scenario's uuid) and linked.
  std::ifstream page_file(dir / "full" / "search.html");
  const std::string page((std::istreambuf_iterator<char>(page_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("lead.speed (km/h)"), std::string::npos);
  EXPECT_NE(page.find(R"(class="best")"), std::string::npos);
  EXPECT_NE(page.find("\">run 1</a>"), std::string::npos);
  EXPECT_NE(page.find(runs[0]["run_dir"].get<std::string>() + "/report.html"), std::string::npos);

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

// Boundary mode on real runs: the 3 x 3 initial grid, then --jobs points at a time, each a
// half point of a grid cell whose corners disagree (a run or an inferred corner never
// repeats), and the estimate in search.json after every iteration.
TEST(SearchCli, BoundaryRefinesOnlyCellsWhoseCornersDisagree) {
  TempDir dir;
  const CliResult r = run_cli({"search", kLeadBrake, "--boundary", "verdict", "--objective", "min_ttc", "--budget", "15",
                               "--jobs", "2", "--set", "lead.brake_time=30", "--max-time", "45", "--out",
                               (dir / "b").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json s = read_json(dir / "b" / "search.json");
  const auto runs = runs_of(s);
  ASSERT_EQ(runs.size(), 15u);
  std::map<std::pair<int, int>, bool> grid;  // the initial grid's outcomes by lattice index
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_EQ(runs[i]["why"], "initial grid") << i;
    const double u = runs[i]["unit"][0].get<double>() * 2, v = runs[i]["unit"][1].get<double>() * 2;
    ASSERT_DOUBLE_EQ(u, std::round(u));
    ASSERT_DOUBLE_EQ(v, std::round(v));
    grid[{static_cast<int>(u), static_cast<int>(v)}] = runs[i]["pass"].get<bool>();
  }
  ASSERT_EQ(grid.size(), 9u);
  for (std::size_t i = 9; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i]["why"], "refine a cell whose corners disagree") << i;
    const double u = runs[i]["unit"][0].get<double>() * 2, v = runs[i]["unit"][1].get<double>() * 2;
    bool disagree = false;  // some grid cell holding the point has corners that disagree
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        if (u < a - 1e-9 || u > a + 1 + 1e-9 || v < b - 1e-9 || v > b + 1 + 1e-9) continue;
        const bool first = grid[{a, b}];
        disagree = disagree || grid[{a + 1, b}] != first || grid[{a, b + 1}] != first || grid[{a + 1, b + 1}] != first;
      }
    EXPECT_TRUE(disagree) << runs[i];
  }
  EXPECT_EQ(s["iterations"].back()["points"].size(), 2u);  // --jobs at a time after the grid
  EXPECT_TRUE(s["iterations"].back().contains("boundary"));
  EXPECT_GT(s["boundary"]["pass"].get<std::string>().size(), 0u);
}
