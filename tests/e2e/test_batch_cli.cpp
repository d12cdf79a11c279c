// `orchestrator sample` and `orchestrator batch` end to end: real child runs on SUMO,
// checked through the files a nightly job and CI read.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include "e2e/test_batch_support.hpp"

using namespace orch::test;
using namespace orch::test::batch;
namespace fs = std::filesystem;

namespace {

fs::path copy_nightly(const TempDir& dir, const std::string& logical_uuid, const std::string& template_name) {
  const fs::path src = source_path("scenarios/nightly");
  fs::copy_file(src / template_name, dir / template_name);
  for (const auto& entry : fs::directory_iterator(src)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("abstract_", 0) == 0 || name.rfind("natural_", 0) == 0) fs::copy_file(entry.path(), dir / name);
  }
  fs::copy_file(src / ("logical_" + logical_uuid + ".json"), dir / ("logical_" + logical_uuid + ".json"));
  return dir / ("logical_" + logical_uuid + ".json");
}

const std::string kLeadBrake = "9202dd94-2666-4583-a45c-f8396b848ae9";

}  // namespace

TEST(BatchCli, SampleWritesTheSeedsShapeAndTheSameSeedGivesTheSameSets) {
  TempDir a, b;
  const auto logical_a = copy_nightly(a, kLeadBrake, "lead_brake.template.json");
  const auto logical_b = copy_nightly(b, kLeadBrake, "lead_brake.template.json");
  ASSERT_EQ(run_cli({"sample", logical_a.string(), "--count", "3", "--seed", "5"}).exit_code, 0);
  const auto first = run_cli({"sample", logical_a.string(), "--count", "2", "--seed", "5", "--max-time", "30"});
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("2 new parameter set(s), 5 in all"), std::string::npos) << first.output;
  ASSERT_EQ(run_cli({"sample", logical_b.string(), "--count", "5", "--seed", "5"}).exit_code, 0);

  const auto pa = read_json(a / ("logical_" + kLeadBrake + "_parameters.json"));
  const auto pb = read_json(b / ("logical_" + kLeadBrake + "_parameters.json"));
  EXPECT_EQ(pa["logical_uuid"], kLeadBrake);
  ASSERT_EQ(pa["parameters"].size(), 5u);
  std::set<long long> seeds;
  for (auto it = pa["parameters"].begin(); it != pa["parameters"].end(); ++it) {
    const auto& set = it.value();
    seeds.insert(set["seed"].get<long long>());
    for (const char* key : {"created_at", "seed", "sampled_values", "sumo_config", "output"}) EXPECT_TRUE(set.contains(key)) << key;
    EXPECT_EQ(set["sumo_config"]["map"], "ALKS_Road");
    EXPECT_EQ(set["sumo_config"]["step"], 0.05);
    EXPECT_TRUE(set["sumo_config"].contains("traffic"));
    EXPECT_TRUE(set["sumo_config"].contains("backend"));
    const double speed = set["sampled_values"]["lead"]["speed"].get<double>();
    EXPECT_GE(speed, 55.0);
    EXPECT_LT(speed, 78.0);
    EXPECT_EQ(set["sampled_values"]["lead"]["initial_gap"], 40.0);
    EXPECT_EQ(set["sampled_values"]["criteria"]["critical_gap"], 10.0);
    // Same seed, same uuid, same values, whichever file and in whatever steps sampled.
    ASSERT_TRUE(pb["parameters"].contains(it.key()));
    EXPECT_EQ(pb["parameters"][it.key()]["sampled_values"], set["sampled_values"]);
  }
  EXPECT_EQ(seeds, (std::set<long long>{5, 6, 7, 8, 9}));  // extending skipped the seeds in use
}

TEST(BatchCli, SampleReportsATemplatePlaceholderThatNamesNoParameter) {
  TempDir dir;
  std::string text = kQuickTemplate;
  const std::string good = "ends at ${q.end} s";
  text.replace(text.find(good), good.size(), "ends at ${q.ende} s");
  dir.write("t.json", text);
  dir.write("logical_x.json", R"({"uuid": "x", "template": "t.json", "parameter_space": {"q": {
    "end": {"distribution": "constant", "value": 0.5}, "start": {"distribution": "constant", "value": 5}}}})");
  const auto r = run_cli({"sample", (dir / "logical_x.json").string(), "--count", "1"});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("t.json:8: error: /scenario/ending_scenes/0/description: placeholder ${q.ende}"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "logical_x_parameters.json"));
}

TEST(BatchCli, BatchRunsEverySetAndWritesTracesSummaryAndJunit) {
  TempDir in, out_root;
  std::vector<QuickSet> sets{{"s-ok", 0.5, 5}, {"s-fail", 2.0, 5}, {"s-err", 0.5, 999999}, {"s-ok2", 0.5, 5}};
  const auto logical = write_quick_batch(in, sets);
  const fs::path out = out_root / "b";
  const auto r = run_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "2", "--retries", "1"});
  EXPECT_EQ(r.exit_code, 2) << r.output;  // one run could not run
  // Without a terminal: one line per finished run.
  EXPECT_NE(r.output.find("[4/4]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("retry"), std::string::npos) << r.output;

  for (const auto& s : sets) {
    const fs::path trace = out / "executions" / ("execution_" + run_id_of(s.uuid) + ".json");
    ASSERT_TRUE(fs::exists(trace)) << trace;
    const auto j = read_json(trace);
    const std::string verdict = expected_verdict(s);
    EXPECT_EQ(j["trace"]["implementation"]["final_status"], verdict) << s.uuid;
    EXPECT_EQ(j["trace"]["implementation"]["exit_code"], verdict == "success" ? 0 : verdict == "failure" ? 1 : 2);
    EXPECT_EQ(j["parameter_uuid"], s.uuid);
    EXPECT_EQ(j["logical_uuid"], kQuickLogicalUuid);
    EXPECT_EQ(j["trace"]["implementation"]["attempts"].size(), verdict == "error" ? 2u : 1u);  // errors retried once
    const std::string command = j["trace"]["implementation"]["command"];
    EXPECT_NE(command.find(" run "), std::string::npos);
    EXPECT_NE(command.find("--max-time 5"), std::string::npos) << command;
    const fs::path run_dir = out / j["outputs"]["run_dir"].get<std::string>();
    EXPECT_TRUE(fs::exists(run_dir / "scenario.json"));
    EXPECT_TRUE(fs::exists(run_dir / "result.json"));
    EXPECT_TRUE(fs::exists(run_dir / "run.log"));
    EXPECT_EQ(read_json(run_dir / "result.json")["verdict"], verdict);
    // The bound scenario holds the set's values with their JSON types.
    EXPECT_EQ(read_json(run_dir / "scenario.json")["scenario"]["opening_scene"]["ego"]["start_position"]["wp_idx"], s.start);
    // An error's first attempt keeps its log; a run that ran has a trace.
    EXPECT_EQ(fs::exists(run_dir / "attempt1.child.log"), verdict == "error") << s.uuid;
    if (verdict != "error") {
      EXPECT_TRUE(fs::exists(run_dir / "trace.csv")) << s.uuid;
    }
  }
  const auto summary = read_json(out / "summary.json");
  EXPECT_EQ(summary["totals"]["runs"], 4);
  EXPECT_EQ(summary["totals"]["success"], 2);
  EXPECT_EQ(summary["totals"]["failure"], 1);
  EXPECT_EQ(summary["totals"]["error"], 1);

  pugi::xml_document junit;
  ASSERT_TRUE(junit.load_file((out / "junit.xml").c_str()));
  int cases = 0, failures = 0, errors = 0;
  for (auto tc : junit.child("testsuites").child("testsuite").children("testcase")) {
    ++cases;
    if (tc.child("failure")) ++failures;
    if (tc.child("error")) {
      ++errors;
      EXPECT_NE(std::string(tc.child("error").attribute("message").value()).find("invalid scenario"), std::string::npos);
    }
  }
  EXPECT_EQ(cases, 4);
  EXPECT_EQ(failures, 1);
  EXPECT_EQ(errors, 1);
  const std::string table = slurp(out / "summary.txt");
  EXPECT_NE(table.find("4 runs: 2 success, 1 failure, 1 error, 0 missing"), std::string::npos) << table;
  EXPECT_NE(table.find("q.end=2"), std::string::npos) << table;
}

TEST(BatchCli, CrashingAndHangingChildrenAreErrorsAndTheBatchGoesOn) {
  TempDir in, out_root;
  std::vector<QuickSet> sets{{"crash", 0.5, 5}, {"hang", 0.5, 5}, {"fine", 0.5, 5}};
  const auto logical = write_quick_batch(in, sets);
  // A wrapper standing in for a broken build: it crashes or hangs (with a child of its own)
  // for two of the runs and starts the real run for the third. The timeout leaves the real
  // run room under AddressSanitizer on two busy cores.
  const fs::path grandchild = in / "grandchild.pid";
  const auto wrapper = in.write("wrapper.sh", "#!/bin/sh\ncase \"$*\" in\n"
                                              "  *crash*) kill -SEGV $$ ;;\n"
                                              "  *hang*) sleep 300 & echo $! > " + grandchild.string() + "; wait ;;\n"
                                              "esac\nexec \"$@\"\n");
  fs::permissions(wrapper, fs::perms::owner_all);
  const fs::path out = out_root / "b";
  const auto r = run_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "3", "--timeout", "10",
                          "--retries", "0", "--wrapper", wrapper.string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto summary = read_json(out / "summary.json");
  std::map<std::string, nlohmann::json> by_id;
  for (const auto& run : summary["runs"]) by_id[run["run_id"]] = run;
  EXPECT_EQ(by_id[run_id_of("fine")]["verdict"], "success");
  EXPECT_EQ(by_id[run_id_of("crash")]["verdict"], "error");
  EXPECT_NE(by_id[run_id_of("crash")]["reason"].get<std::string>().find("signal 11"), std::string::npos);
  EXPECT_EQ(by_id[run_id_of("hang")]["verdict"], "error");
  EXPECT_NE(by_id[run_id_of("hang")]["reason"].get<std::string>().find("timed out after 10 s"), std::string::npos);
  // The hanging run's own child went with it.
  const pid_t pid = std::stoi(slurp(grandchild));
  EXPECT_FALSE(process_running(pid)) << "the hanging run's child " << pid << " survived its timeout";
}

TEST(BatchCli, ExecutionTraceLinksBackToTheAbstractAndTheRequirement) {
  TempDir dir;
  const auto logical = copy_nightly(dir, kLeadBrake, "lead_brake.template.json");
  ASSERT_EQ(run_cli({"sample", logical.string(), "--count", "1", "--seed", "3", "--max-time", "0.5"}).exit_code, 0);
  const fs::path out = dir / "b";
  const auto r = run_cli({"batch", logical.string(), "--out", out.string()});
  ASSERT_LE(r.exit_code, 1) << r.output;
  fs::path trace;
  for (const auto& e : fs::directory_iterator(out / "executions")) trace = e.path();
  ASSERT_EQ(trace.filename().string().rfind("execution_" + kLeadBrake + "_", 0), 0u) << trace;
  const auto j = read_json(trace);
  EXPECT_EQ(j["abstract_uuid"], "7f48f89d-b112-46d0-be92-7b49dc785efb");
  EXPECT_EQ(fs::path(j["trace"]["abstract_scenario_file"].get<std::string>()).filename(),
            "abstract_7f48f89d-b112-46d0-be92-7b49dc785efb.json");
  EXPECT_EQ(fs::path(j["trace"]["natural_scenario_file"].get<std::string>()).filename(),
            "natural_f57eca24-bc2b-4f3d-9a59-3ebf9f322126.json");
  EXPECT_NE(j["trace"]["original_prompt"].get<std::string>().find("brakes hard"), std::string::npos);
  // Through the parameter file to the sampled values.
  const auto params = read_json(j["trace"]["parameter_file"].get<std::string>());
  EXPECT_EQ(params["parameters"][j["parameter_uuid"].get<std::string>()]["sampled_values"], j["trace"]["sampled_values"]);
}

TEST(BatchCli, ARunSettingTheRunCommandLacksIsRefusedBeforeAnythingRuns) {
  TempDir in;
  const auto logical = write_quick_batch(in, {{"s", 0.5, 5}});
  auto params = read_json(in / (std::string("logical_") + kQuickLogicalUuid + "_parameters.json"));
  params["parameters"]["s"]["sumo_config"]["traffic"] = "dense";
  in.write(std::string("logical_") + kQuickLogicalUuid + "_parameters.json", params.dump(2));
  const bool run_has_traffic = run_cli({"run", "--help"}).output.find("--traffic") != std::string::npos;
  const auto r = run_cli({"batch", logical.string(), "--out", (in / "b").string(), "--retries", "0"});
  if (run_has_traffic) {
    // Passed through as it is; whatever `run` makes of "dense" is its business.
    const auto trace = read_json(in / "b" / "executions" / ("execution_" + run_id_of("s") + ".json"));
    EXPECT_NE(trace["trace"]["implementation"]["command"].get<std::string>().find("--traffic dense"), std::string::npos);
  } else {
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("has no --traffic option"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(in / "b" / "runs" / run_id_of("s")));
  }
}

TEST(BatchCli, AFolderHoldingABatchIsOnlyContinuedWithResume) {
  TempDir in;
  const auto logical = write_quick_batch(in, {{"s", 0.5, 5}});
  const fs::path out = in / "b";
  ASSERT_EQ(run_cli({"batch", logical.string(), "--out", out.string()}).exit_code, 0);
  const auto again = run_cli({"batch", logical.string(), "--out", out.string()});
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.output.find("--resume"), std::string::npos) << again.output;
  // A changed input makes the old results belong to something else: refused.
  in.write("quick.template.json", std::string(kQuickTemplate) + "\n");
  const auto changed = run_cli({"batch", "--resume", out.string()});
  EXPECT_EQ(changed.exit_code, 2);
  EXPECT_NE(changed.output.find("changed since the batch started"), std::string::npos) << changed.output;
}

TEST(BatchCli, ShardsRunDisjointHalvesAndTheirMergeEqualsTheWholeBatch) {
  TempDir in;
  const auto sets = mixed_sets(5);
  const auto logical = write_quick_batch(in, sets);
  ASSERT_EQ(run_cli({"batch", logical.string(), "--out", (in / "whole").string(), "--jobs", "2"}).exit_code, 1);
  for (const char* shard : {"1/2", "2/2"}) {
    const auto r = run_cli({"batch", logical.string(), "--shard", shard, "--out", (in / ("shard" + std::string(1, shard[0]))).string()});
    ASSERT_LE(r.exit_code, 1) << r.output;
  }
  const auto s1 = verdicts_of(in / "shard1" / "summary.json");
  const auto s2 = verdicts_of(in / "shard2" / "summary.json");
  EXPECT_EQ(s1.size() + s2.size(), sets.size());
  EXPECT_GE(s1.size(), 2u);
  EXPECT_GE(s2.size(), 2u);
  for (const auto& [id, verdict] : s1) EXPECT_EQ(s2.count(id), 0u) << id;

  // One shard alone is an incomplete batch: merged, its missing runs are errors.
  const auto partial = run_cli({"batch", "merge", (in / "shard1").string(), "--out", (in / "partial").string()});
  EXPECT_EQ(partial.exit_code, 2) << partial.output;
  EXPECT_EQ(read_json(in / "partial" / "summary.json")["totals"]["missing"].get<std::size_t>(), s2.size());

  const auto merged = run_cli({"batch", "merge", (in / "shard1").string(), (in / "shard2").string(), "--out",
                               (in / "merged").string()});
  EXPECT_EQ(merged.exit_code, 1) << merged.output;
  EXPECT_EQ(verdicts_of(in / "merged" / "summary.json"), verdicts_of(in / "whole" / "summary.json"));
  EXPECT_EQ(read_json(in / "merged" / "summary.json")["totals"], read_json(in / "whole" / "summary.json")["totals"]);
  pugi::xml_document junit;
  ASSERT_TRUE(junit.load_file((in / "merged" / "junit.xml").c_str()));
  EXPECT_EQ(junit.child("testsuites").attribute("tests").as_int(), 5);
  // Merging a shard twice would count its runs twice: refused.
  const auto twice = run_cli({"batch", "merge", (in / "shard1").string(), (in / "shard1").string(), "--out",
                              (in / "twice").string()});
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.output.find("merge each shard once"), std::string::npos) << twice.output;
}
