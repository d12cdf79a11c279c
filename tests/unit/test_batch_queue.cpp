// The process queue of a batch (children are small shell commands, no SUMO) and the
// verdict of an attempt from how its child ended.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <thread>

#include "batch/attempt.hpp"
#include "batch/run_queue.hpp"
#include "support/cli_runner.hpp"

using namespace orch::batch;
using orch::test::TempDir;

namespace {

Launch shell(const std::string& script, const TempDir& dir, std::size_t task) {
  return Launch{{"/bin/sh", "-c", script}, dir / ("task" + std::to_string(task) + ".log")};
}

// A process that is gone or a zombie no longer runs.
bool process_running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return false;
  const auto close = text.rfind(')');
  return close != std::string::npos && text.size() > close + 2 && text[close + 2] != 'Z';
}

}  // namespace

TEST(BatchQueue, RunsExactlyJobsChildrenAtATime) {
  TempDir dir;
  int in_flight = 0, most = 0, ended = 0;
  QueueCallbacks cb;
  cb.prepare = [&](std::size_t task, int) {
    most = std::max(most, ++in_flight);
    return shell("sleep 0.3", dir, task);
  };
  cb.ended = [&](std::size_t, int, const ChildExit& exit, const std::string&) {
    --in_flight;
    ++ended;
    EXPECT_EQ(exit.exit_code, 0);
    return false;
  };
  const auto outcome = run_queue({0, 1, 2, 3, 4}, QueueOptions{2, std::nullopt, 0.1}, cb);
  EXPECT_FALSE(outcome.interrupted);
  EXPECT_EQ(ended, 5);
  EXPECT_EQ(most, 2);
}

TEST(BatchQueue, TimeoutKillsTheWholeProcessTree) {
  TempDir dir;
  const std::string pid_file = (dir / "grandchild.pid").string();
  std::optional<ChildExit> seen;
  QueueCallbacks cb;
  cb.prepare = [&](std::size_t task, int) {
    return shell("sleep 60 & echo $! > " + pid_file + "; wait", dir, task);
  };
  cb.ended = [&](std::size_t, int, const ChildExit& exit, const std::string&) {
    seen = exit;
    return false;
  };
  run_queue({0}, QueueOptions{1, 0.5, 0.1}, cb);
  ASSERT_TRUE(seen);
  EXPECT_TRUE(seen->timed_out);
  EXPECT_EQ(seen->signal, SIGKILL);
  EXPECT_LT(seen->wall_time_s, 5.0);
  std::ifstream in(pid_file);
  pid_t grandchild = 0;
  ASSERT_TRUE(in >> grandchild);
  for (int i = 0; i < 50 && process_running(grandchild); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(process_running(grandchild)) << "the sleeping grandchild " << grandchild << " survived";
}

TEST(BatchQueue, RetriesWhatTheCallerAsksForAndReportsCrashesAndFailedStarts) {
  TempDir dir;
  std::vector<std::pair<std::size_t, int>> prepared;
  std::map<std::size_t, ChildExit> last;
  std::map<std::size_t, std::string> start_errors;
  QueueCallbacks cb;
  cb.prepare = [&](std::size_t task, int attempt) {
    prepared.emplace_back(task, attempt);
    if (task == 0) return shell("kill -SEGV $$", dir, task);
    if (task == 1) return Launch{{"/nonexistent/program"}, dir / "t1.log"};
    if (task == 2) throw std::runtime_error("cannot bind the template");
    return shell("exit 1", dir, task);
  };
  cb.ended = [&](std::size_t task, int attempt, const ChildExit& exit, const std::string& error) {
    last[task] = exit;
    start_errors[task] = error;
    return task == 0 && attempt < 3;  // only the crashing task is retried, twice
  };
  run_queue({0, 1, 2, 3}, QueueOptions{2, std::nullopt, 0.1}, cb);
  EXPECT_EQ(std::count(prepared.begin(), prepared.end(), std::make_pair<std::size_t, int>(0, 3)), 1);
  EXPECT_EQ(std::count_if(prepared.begin(), prepared.end(), [](auto p) { return p.first == 0; }), 3);
  EXPECT_EQ(last[0].signal, SIGSEGV);
  EXPECT_EQ(last[1].exit_code, 127);  // exec failed in the child
  EXPECT_EQ(start_errors[2], "cannot bind the template");
  EXPECT_EQ(last[3].exit_code, 1);
}

TEST(BatchQueue, SigtermKillsRunningChildrenAndLeavesTheirTasksUnfinished) {
  TempDir dir;
  int ended = 0;
  bool sent = false;
  QueueCallbacks cb;
  cb.prepare = [&](std::size_t task, int) { return shell(task == 0 ? "exit 0" : "sleep 60", dir, task); };
  cb.ended = [&](std::size_t, int, const ChildExit&, const std::string&) {
    ++ended;
    return false;
  };
  cb.tick = [&] {
    if (ended == 1 && !sent) {
      sent = true;
      ::kill(::getpid(), SIGTERM);  // blocked during the queue: received by it, not fatal
    }
  };
  const auto start = std::chrono::steady_clock::now();
  const auto outcome = run_queue({0, 1, 2, 3}, QueueOptions{2, std::nullopt, 0.05}, cb);
  EXPECT_TRUE(outcome.interrupted);
  EXPECT_EQ(ended, 1);
  EXPECT_EQ(outcome.unfinished, (std::vector<std::size_t>{1, 2, 3}));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

// ------------------------------------------------------------------ attempt verdicts

namespace {

std::filesystem::path result_file(const TempDir& dir, const std::string& verdict) {
  return dir.write("result.json", R"({"verdict": ")" + verdict + R"(", "reason": "because", "sim_time": 12.5,
                                  "wall_time_s": 0.25, "other": [1, 2]})");
}

ChildExit exited(int code) {
  ChildExit e;
  e.exit_code = code;
  e.wall_time_s = 1.5;
  return e;
}

}  // namespace

TEST(BatchAttempt, ExitCodeAndResultTogetherGiveTheVerdict) {
  TempDir dir;
  auto a = judge_attempt(exited(0), "", result_file(dir, "success"), 60);
  EXPECT_EQ(a.verdict, "success");
  EXPECT_EQ(a.sim_time, 12.5);
  EXPECT_EQ(a.run_wall_time_s, 0.25);
  a = judge_attempt(exited(1), "", result_file(dir, "failure"), 60);
  EXPECT_EQ(a.verdict, "failure");
  EXPECT_EQ(a.reason, "because");
  a = judge_attempt(exited(2), "", result_file(dir, "error"), 60);
  EXPECT_EQ(a.verdict, "error");
  EXPECT_EQ(a.reason, "because");
}

TEST(BatchAttempt, AnythingInconsistentIsAnErrorNeverAFailure) {
  TempDir dir;
  auto a = judge_attempt(exited(0), "", result_file(dir, "failure"), 60);
  EXPECT_EQ(a.verdict, "error");
  EXPECT_NE(a.reason.find("contradicts"), std::string::npos);
  a = judge_attempt(exited(1), "", dir / "none.json", 60);
  EXPECT_EQ(a.verdict, "error");
  EXPECT_NE(a.reason.find("no result.json"), std::string::npos);
  dir.write("torn.json", R"({"verdict": "succ)");
  a = judge_attempt(exited(0), "", dir / "torn.json", 60);
  EXPECT_EQ(a.verdict, "error");
  EXPECT_NE(a.reason.find("unreadable"), std::string::npos);
  ChildExit crashed;
  crashed.signal = SIGSEGV;
  a = judge_attempt(crashed, "", result_file(dir, "success"), 60);
  EXPECT_EQ(a.verdict, "error");
  EXPECT_NE(a.reason.find("signal 11"), std::string::npos);
  ChildExit slow;
  slow.signal = SIGKILL;
  slow.timed_out = true;
  a = judge_attempt(slow, "", dir / "none.json", 42);
  EXPECT_NE(a.reason.find("timed out after 42 s"), std::string::npos);
}

TEST(BatchAttempt, OnlyErrorsAreRetriedAndOnlyUpToTheLimit) {
  Attempt a;
  a.verdict = "error";
  a.number = 1;
  EXPECT_TRUE(should_retry(a, 2));
  a.number = 2;
  EXPECT_FALSE(should_retry(a, 2));
  a.number = 1;
  a.verdict = "failure";
  EXPECT_FALSE(should_retry(a, 5));
}
