// scripts/cluster/: the logic every cluster runs a shard with (run_shard.sh, here with a
// stand-in orchestrator that records its arguments), and the Kubernetes Indexed Job's
// manifest (this machine has no Kubernetes: its structure and the shard mapping are checked).
// The Slurm job array runs for real in tests/integration/test_batch_slurm.cpp.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "support/cli_runner.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

struct ShardCall {
  int exit_code;
  std::string args;  // what the stand-in orchestrator was called with
};

ShardCall run_shard(const TempDir& dir, int fake_status, const std::string& out) {
  const auto fake = dir.write("fake_orchestrator.sh", "#!/bin/sh\necho \"$*\" >> " + (dir / "calls.txt").string() +
                                                          "\nexit " + std::to_string(fake_status) + "\n");
  fs::permissions(fake, fs::perms::owner_all);
  fs::remove(dir / "calls.txt");
  const std::string cmd = "ORCHESTRATOR=" + shell_quote(fake.string()) + " JOBS=3 " +
                          shell_quote(source_path("scripts/cluster/run_shard.sh")) + " 2 5 " + shell_quote(out) +
                          " a.json b.json >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  std::string args = slurp(dir / "calls.txt");
  if (!args.empty() && args.back() == '\n') args.pop_back();
  return {WEXITSTATUS(status), args};
}

}  // namespace

TEST(BatchClusterScripts, RunShardStartsItsShardOrResumesIt) {
  TempDir dir;
  const std::string out = (dir / "results").string();
  auto call = run_shard(dir, 0, out);
  EXPECT_EQ(call.exit_code, 0);
  EXPECT_EQ(call.args, "batch a.json b.json --shard 2/5 --out " + out + "/shard_2 --jobs 3");
  // Started again after being killed: its folder holds a batch, so it resumes.
  fs::create_directories(dir / "results" / "shard_2");
  dir.write("results/shard_2/batch.json", "{}");
  call = run_shard(dir, 0, out);
  EXPECT_EQ(call.args, "batch --resume " + out + "/shard_2 --jobs 3");
}

TEST(BatchClusterScripts, RunShardTurnsVerdictsIntoSuccessButNotInterruptions) {
  TempDir dir;
  const std::string out = (dir / "results").string();
  EXPECT_EQ(run_shard(dir, 1, out).exit_code, 0);  // failures: reported by the merge, not retried
  EXPECT_EQ(run_shard(dir, 2, out).exit_code, 0);  // errors: the same
  EXPECT_EQ(run_shard(dir, 3, out).exit_code, 3);  // interrupted: the scheduler retries, which resumes
  EXPECT_EQ(run_shard(dir, 137, out).exit_code, 137);
}

TEST(BatchClusterScripts, KubernetesIndexedJobRunsOneShardPerIndex) {
  const YAML::Node job = YAML::LoadFile(source_path("scripts/cluster/k8s_indexed_job.yaml"));
  EXPECT_EQ(job["apiVersion"].as<std::string>(), "batch/v1");
  EXPECT_EQ(job["kind"].as<std::string>(), "Job");
  const auto spec = job["spec"];
  EXPECT_EQ(spec["completionMode"].as<std::string>(), "Indexed");
  const int completions = spec["completions"].as<int>();
  EXPECT_EQ(spec["parallelism"].as<int>(), completions);
  const auto pod = spec["template"]["spec"];
  EXPECT_EQ(pod["restartPolicy"].as<std::string>(), "OnFailure");  // a killed shard resumes
  const auto container = pod["containers"][0];
  std::string shards;
  for (const auto& env : container["env"])
    if (env["name"].as<std::string>() == "SHARDS") shards = env["value"].as<std::string>();
  EXPECT_EQ(shards, std::to_string(completions)) << "SHARDS must equal completions";
  const std::string args = container["args"][0].as<std::string>();
  // Indexes 0..N-1 become shards 1..N of run_shard.sh.
  EXPECT_NE(args.find("run_shard.sh \"$((JOB_COMPLETION_INDEX + 1))\" \"$SHARDS\""), std::string::npos) << args;
  bool mounted = false;
  for (const auto& m : container["volumeMounts"]) mounted = mounted || m["mountPath"].as<std::string>() == "/results";
  EXPECT_TRUE(mounted);
  EXPECT_NE(args.find(" /results "), std::string::npos) << args;
}
