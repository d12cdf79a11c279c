// Nothing lost, nothing counted twice: a batch SIGKILLed at random moments, again and
// again, and resumed each time, ends with exactly one execution trace per run, each
// readable and with the verdict its parameters dictate, and no run that was done is run
// again.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <thread>

#include "e2e/test_batch_support.hpp"

using namespace orch::test;
using namespace orch::test::batch;
namespace fs = std::filesystem;

namespace {

// Execution traces present in the folder: name -> bytes. Temporary files of a write that
// a kill interrupted are not traces (the next resume removes them); `temporaries` counts them.
std::map<std::string, std::string> traces_in(const fs::path& out, int* temporaries = nullptr) {
  std::map<std::string, std::string> out_map;
  if (!fs::exists(out / "executions")) return out_map;
  for (const auto& e : fs::directory_iterator(out / "executions")) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp") != std::string::npos) {
      if (temporaries) ++*temporaries;
      continue;
    }
    out_map[name] = slurp(e.path());
  }
  return out_map;
}

void wait_until_gone(const std::string& mention) {
  for (int i = 0; i < 100 && !processes_mentioning(mention).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

}  // namespace

TEST(BatchResume, RandomSigkillsThenResumeRunExactlyTheMissingRuns) {
  TempDir in;
  const auto sets = mixed_sets(16);
  const auto logical = write_quick_batch(in, sets);
  const fs::path out = in / "batch";
  const fs::path log = in / "batch.log";

  // The moments are drawn from a fixed seed (the test command is deterministic; the moments
  // still fall on different work from machine to machine). Half the kills come at any
  // moment, half just after a run finished (while the next traces and result files are being
  // written), so that both kinds of moment are hit every time.
  const unsigned seed = 20261127;
  std::mt19937 rng(seed);
  // Well within the time the whole batch takes (16 quick runs, 2 at a time: 1.1 s and more
  // with libsumo's stand-ins, 0.07 s a run), so that the first kill always comes before the
  // batch is done.
  std::uniform_int_distribution<int> any_moment_ms(50, 600);
  std::uniform_int_distribution<int> after_a_run_ms(0, 150);
  SCOPED_TRACE("kill schedule seed " + std::to_string(seed));

  int kills = 0;
  bool started = false;
  std::string schedule;
  for (int round = 0; round < 8; ++round) {
    const auto before = traces_in(out);
    if (before.size() == sets.size()) break;
    std::vector<std::string> args = started ? std::vector<std::string>{"batch", "--resume", out.string()}
                                            : std::vector<std::string>{"batch", logical.string(), "--out", out.string(),
                                                                       "--jobs", "2"};
    // Before the first batch.json exists, a kill leaves nothing to resume: start afresh.
    const pid_t pid = start_cli(args, log);
    int ms = 0;
    if (round % 2 == 0) {
      ms = any_moment_ms(rng);
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    } else {
      const auto t0 = std::chrono::steady_clock::now();
      while (traces_in(out).size() == before.size() &&
             std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      std::this_thread::sleep_for(std::chrono::milliseconds(after_a_run_ms(rng)));
      ms = static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count());
    }
    const bool killed = ::kill(pid, SIGKILL) == 0;
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (killed && WIFSIGNALED(status)) ++kills;
    started = fs::exists(out / "batch.json");
    schedule += " " + std::to_string(ms) + "ms:" + std::to_string(traces_in(out).size()) + "done";

    // The children died with their batch (no orphan keeps writing into the folder).
    wait_until_gone(out.string());
    EXPECT_TRUE(processes_mentioning(out.string()).empty()) << "orphans after the kill after " << ms << " ms";
    // No run that was done was touched, and every trace there is whole.
    const auto after = traces_in(out);
    for (const auto& [name, bytes] : before) {
      ASSERT_TRUE(after.count(name)) << name << " vanished";
      EXPECT_EQ(after.at(name), bytes) << name << " was written again: a run done twice";
    }
    for (const auto& [name, bytes] : after)
      EXPECT_TRUE(nlohmann::json::accept(bytes)) << name << " is torn";
  }
  std::cout << "kill schedule (seed " << seed << "):" << schedule << "\n";
  EXPECT_GE(kills, 1) << slurp(log);

  const auto before_final = traces_in(out);
  const auto final_run = started ? run_cli({"batch", "--resume", out.string()})
                                 : run_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "2"});
  EXPECT_EQ(final_run.exit_code, 1) << final_run.output;  // some sets fail by design, none errs
  int temporaries = 0;
  const auto after_final = traces_in(out, &temporaries);
  for (const auto& [name, bytes] : before_final) EXPECT_EQ(after_final.at(name), bytes) << name << " was run twice";

  // Exactly one trace per run, no leftovers, every verdict the one its values dictate.
  EXPECT_EQ(after_final.size(), sets.size());
  EXPECT_EQ(temporaries, 0);
  const auto verdicts = verdicts_of(out / "summary.json");
  ASSERT_EQ(verdicts.size(), sets.size()) << slurp(out / "summary.json") << final_run.output;
  for (const auto& s : sets) EXPECT_EQ(verdicts.at(run_id_of(s.uuid)), expected_verdict(s)) << s.uuid;
  const auto summary = read_json(out / "summary.json");
  EXPECT_EQ(summary["totals"]["missing"], 0);
  EXPECT_EQ(summary["totals"]["success"].get<int>() + summary["totals"]["failure"].get<int>(), static_cast<int>(sets.size()));
  // Every run folder holds the outputs of one complete attempt.
  for (const auto& s : sets) {
    const fs::path dir = out / "runs" / run_id_of(s.uuid);
    EXPECT_EQ(read_json(dir / "result.json")["verdict"], expected_verdict(s)) << s.uuid;
  }
}

TEST(BatchResume, SigtermStopsTheBatchCleanlyAndResumeFinishesIt) {
  TempDir in;
  const auto sets = mixed_sets(6);
  const auto logical = write_quick_batch(in, sets);
  const fs::path out = in / "batch";
  // --ego-model is kept in batch.json: the resumed runs drive their ego as the first ones did.
  const pid_t pid =
      start_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "1", "--ego-model", "sumo"}, in / "log");
  // Stop it once the first run is done.
  for (int i = 0; i < 600 && traces_in(out).empty(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << slurp(in / "log");
  EXPECT_EQ(WEXITSTATUS(status), 3) << slurp(in / "log");  // interrupted: to be resumed
  EXPECT_NE(slurp(in / "log").find("--resume"), std::string::npos);
  const auto done = traces_in(out).size();
  EXPECT_GE(done, 1u);
  EXPECT_LT(done, sets.size());
  EXPECT_GT(read_json(out / "summary.json")["totals"]["missing"].get<int>(), 0);

  const auto resumed = run_cli({"batch", "--resume", out.string()});
  EXPECT_EQ(resumed.exit_code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(sets.size() - done) + " to run"), std::string::npos) << resumed.output;
  EXPECT_EQ(traces_in(out).size(), sets.size());
  EXPECT_EQ(read_json(out / "summary.json")["totals"]["missing"], 0);
  for (const auto& [name, text] : traces_in(out)) {
    const auto command = nlohmann::json::parse(text)["trace"]["implementation"]["command"].get<std::string>();
    EXPECT_NE(command.find("--ego-model sumo"), std::string::npos) << name << ": " << command;
  }
}
