// Reports of a batch from its folder(s): totals, JUnit XML, the table, merging shards,
// and refusing what would count a run twice.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include "batch/batch_report.hpp"
#include "batch/manifest.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"
#include "support/cli_runner.hpp"

using namespace orch;
using namespace orch::batch;
using orch::test::TempDir;

namespace {

PlannedLogical logical(const std::string& uuid, const std::string& name) {
  PlannedLogical l;
  l.logical.uuid = uuid;
  l.logical.name = name;
  l.logical.file = "/data/logical_" + uuid + ".json";
  l.logical.template_file = "/data/t.json";
  l.parameter_file = "/data/logical_" + uuid + "_parameters.json";
  l.lineage.abstract_uuid = "A1";
  l.lineage.abstract_file = "/data/abstract_A1.json";
  return l;
}

PlannedRun run(const std::string& logical_uuid, const std::string& set_uuid, long long seed, double gap) {
  PlannedRun r;
  r.logical_uuid = logical_uuid;
  r.parameter_uuid = set_uuid;
  r.id = run_id(logical_uuid, set_uuid);
  r.name = "Cut-in";
  r.set.uuid = set_uuid;
  r.set.seed = seed;
  r.set.sampled_values = {{"cut_in", {{"gap", gap}}}};
  return r;
}

// A batch folder holding `runs` planned, of which those with a verdict in `verdicts` done.
void make_folder(const std::filesystem::path& dir, const std::vector<PlannedRun>& runs,
                 const std::map<std::string, std::string>& verdicts, std::size_t total, std::optional<Shard> shard) {
  BatchPlan plan;
  plan.runs = runs;
  plan.total_runs = total;
  plan.shard = shard;
  std::filesystem::create_directories(dir / "executions");
  write_file_atomically(manifest_path(dir), manifest_text(plan, {{"jobs", 2}}));
  const PlannedLogical l = logical("L1", "Cut-in");
  for (const auto& r : runs) {
    const auto it = verdicts.find(r.parameter_uuid);
    if (it == verdicts.end()) continue;
    ExecutionRecord rec;
    rec.execution_uuid = "E-" + r.parameter_uuid;
    rec.command = {"/bin/orchestrator", "run", "scenario.json", "--out", "runs/x y"};
    Attempt a;
    a.verdict = it->second;
    a.reason = it->second == "success" ? "ending scene 5 reached" : "stop condition: actor 0 collided <&>";
    a.exit_code = it->second == "success" ? 0 : it->second == "failure" ? 1 : 2;
    a.wall_time_s = 2.5;
    a.sim_time = 20;
    rec.attempts = {a};
    write_file_atomically(execution_trace_path(dir, r.id), execution_trace_text(r, l, rec));
  }
}

}  // namespace

TEST(BatchReport, ExecutionTraceHasTheSeedsShapeAndLinks) {
  TempDir dir;
  const auto r = run("L1", "P1", 7, 12.5);
  make_folder(dir.path(), {r}, {{"P1", "failure"}}, 1, std::nullopt);
  const auto j = orch::test::read_json(execution_trace_path(dir.path(), r.id));
  for (const char* key : {"execution_uuid", "logical_uuid", "abstract_uuid", "parameter_uuid", "name", "description",
                          "executed_at", "trace", "outputs"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["abstract_uuid"], "A1");
  EXPECT_EQ(j["trace"]["abstract_scenario_file"], "/data/abstract_A1.json");
  EXPECT_EQ(j["trace"]["logical_scenario_file"], "/data/logical_L1.json");
  EXPECT_EQ(j["trace"]["parameter_file"], "/data/logical_L1_parameters.json");
  EXPECT_EQ(j["trace"]["parameter_uuid"], "P1");
  EXPECT_EQ(j["trace"]["implementation"]["exit_code"], 1);
  EXPECT_EQ(j["trace"]["implementation"]["final_status"], "failure");
  EXPECT_EQ(j["trace"]["implementation"]["command"], "/bin/orchestrator run scenario.json --out 'runs/x y'");
  EXPECT_EQ(j["outputs"]["result_file"], "runs/L1_P1/result.json");
  const auto s = read_execution_summary(execution_trace_path(dir.path(), r.id));
  EXPECT_EQ(s.verdict, "failure");
  EXPECT_EQ(s.seed, 7);
  EXPECT_EQ(s.sampled_values["cut_in"]["gap"], 12.5);
}

TEST(BatchReport, TotalsJunitAndTableCountEachRunOnce) {
  TempDir dir;
  const std::vector<PlannedRun> runs{run("L1", "P1", 1, 5), run("L1", "P2", 2, 10), run("L1", "P3", 3, 15),
                                     run("L1", "P4", 4, 20)};
  make_folder(dir.path(), runs, {{"P1", "success"}, {"P2", "failure"}, {"P3", "error"}}, 4, std::nullopt);
  const BatchReport report = collect_report({dir.path()});
  const auto t = report.totals();
  EXPECT_EQ(t.success, 1u);
  EXPECT_EQ(t.failure, 1u);
  EXPECT_EQ(t.error, 1u);
  EXPECT_EQ(t.missing, 1u);
  EXPECT_EQ(batch_exit_code(t), 2);

  pugi::xml_document xml;
  ASSERT_TRUE(xml.load_string(junit_xml(report).c_str()));
  const auto suites = xml.child("testsuites");
  EXPECT_EQ(suites.attribute("tests").as_int(), 4);
  EXPECT_EQ(suites.attribute("failures").as_int(), 1);
  EXPECT_EQ(suites.attribute("errors").as_int(), 2);  // the error and the missing run
  const auto suite = suites.child("testsuite");
  EXPECT_STREQ(suite.attribute("name").value(), "Cut-in");
  int cases = 0;
  for (auto tc : suite.children("testcase")) {
    ++cases;
    if (std::string(tc.attribute("name").value()).rfind("P2", 0) == 0) {
      EXPECT_STREQ(tc.child("failure").attribute("message").value(), "stop condition: actor 0 collided <&>");
      EXPECT_NE(std::string(tc.child("failure").text().get()).find("cut_in.gap=10"), std::string::npos);
    }
  }
  EXPECT_EQ(cases, 4);

  const std::string table = summary_table(report);
  EXPECT_NE(table.find("4 runs: 1 success, 1 failure, 1 error, 1 missing"), std::string::npos) << table;
  EXPECT_NE(table.find("values: cut_in.gap=10"), std::string::npos) << table;
  EXPECT_EQ(table.find("values: cut_in.gap=5"), std::string::npos) << table;  // successes are not listed

  write_reports(report, dir.path());
  const auto summary = orch::test::read_json(dir / "summary.json");
  EXPECT_EQ(summary["totals"]["missing"], 1);
  EXPECT_EQ(summary["runs"][3]["verdict"], "missing");
  EXPECT_EQ(summary["runs"][1]["run_dir"], "runs/L1_P2");
}

TEST(BatchReport, MergeOfShardsCombinesAndRefusesDuplicatesAndStrangers) {
  TempDir a, b, c, merged;
  const std::vector<PlannedRun> all{run("L1", "P1", 1, 5), run("L1", "P2", 2, 10), run("L1", "P3", 3, 15)};
  make_folder(a.path(), {all[0], all[2]}, {{"P1", "success"}, {"P3", "failure"}}, 3, Shard{1, 2});
  make_folder(b.path(), {all[1]}, {{"P2", "success"}}, 3, Shard{2, 2});
  const BatchReport report = collect_report({a.path(), b.path()});
  const auto t = report.totals();
  EXPECT_EQ(t.success + t.failure, 3u);
  EXPECT_EQ(t.missing, 0u);
  EXPECT_EQ(batch_exit_code(t), 1);
  write_reports(report, merged.path());
  const auto summary = orch::test::read_json(merged / "summary.json");
  EXPECT_EQ(summary["shards"], (nlohmann::json{"1/2", "2/2"}));
  // Paths lead from the merged folder to each shard's run folders.
  EXPECT_TRUE(std::filesystem::exists(merged.path() / summary["runs"][0]["execution_file"].get<std::string>()));

  // One shard only: the other's runs are missing, not forgotten.
  EXPECT_EQ(collect_report({a.path()}).totals().missing, 1u);
  EXPECT_THROW(collect_report({a.path(), a.path()}), OrchError);
  make_folder(c.path(), {run("L9", "P9", 9, 1)}, {}, 7, Shard{2, 2});
  EXPECT_THROW(collect_report({a.path(), c.path()}), OrchError);
}

TEST(BatchReport, ShardsPartitionTheRunsAndParseStrictly) {
  std::vector<std::string> ids;
  for (int i = 0; i < 23; ++i) ids.push_back("L_" + std::to_string(i * 7919 % 1000));
  std::sort(ids.begin(), ids.end());
  std::map<std::string, int> owners;
  std::vector<int> sizes(4, 0);
  for (int k = 1; k <= 4; ++k)
    for (const auto& id : ids)
      if (in_shard(ids, id, Shard{k, 4})) {
        ++owners[id];
        ++sizes[static_cast<std::size_t>(k - 1)];
      }
  for (const auto& id : ids) EXPECT_EQ(owners[id], 1) << id;
  for (int s : sizes) EXPECT_GE(s, 5);  // 23 runs over 4 shards: 5 or 6 each
  EXPECT_EQ(parse_shard("3/4").index, 3);
  EXPECT_THROW(parse_shard("0/4"), OrchError);
  EXPECT_THROW(parse_shard("5/4"), OrchError);
  EXPECT_THROW(parse_shard("1/4x"), OrchError);
  EXPECT_THROW(parse_shard("14"), OrchError);
}
