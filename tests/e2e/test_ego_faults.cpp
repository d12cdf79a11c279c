// `orchestrator run --ego-port` when the plug-in misbehaves: it never comes, vanishes,
// stops answering, or sends garbage. Each run must end promptly with verdict error, a reason
// that says what happened and when, and its trace and result written.
#include <gtest/gtest.h>

#include <csignal>

#include "support/ego_plugin_run.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kScenario = source_path("scenarios/alks_obstacle_stop.json");

std::vector<std::string> drive(const std::string& mode, int after, const TempDir& out) {
  return python_client("drive.py", {"--port", "{port}", "--mode", mode, "--after", std::to_string(after),
                                    "--summary", (out / "summary.json").string()});
}

void expect_error_with_outputs(const PluginRun& r, const TempDir& out, const std::string& reason_start) {
  EXPECT_EQ(r.orchestrator_exit, 2) << r.orchestrator_output;
  EXPECT_EQ(r.result["verdict"], "error");
  const std::string reason = r.result["reason"];
  EXPECT_EQ(reason.rfind(reason_start, 0), 0u) << reason;
  EXPECT_TRUE(std::filesystem::exists(out / "trace.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "run.log"));
}

}  // namespace

TEST(EgoFaults, NobodyConnectsWithinTheWaitAndTheRunEndsWithAClearError) {
  TempDir out;
  const int port = free_port();
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_cli({"run", kScenario, "--out", out.path().string(), "-q", "--ego-port", std::to_string(port),
                          "--ego-wait", "1"});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  EXPECT_EQ(result["reason"], "no ego plug-in connected to 127.0.0.1:" + std::to_string(port) +
                                  " within 1 s (--ego-wait)");
  EXPECT_TRUE(result["ego_plugin"]["peer"].is_null());
  EXPECT_LT(wall, 20.0);
}

TEST(EgoFaults, APluginThatDisconnectsMidRunEndsItWithTheTimeItLeft) {
  TempDir out;
  const auto r = run_with_plugin(kScenario, out, drive("disconnect", 20, out));
  expect_error_with_outputs(r, out, "ego disconnected at t=1.050 s");
  EXPECT_EQ(r.result["ego_plugin"]["steps_driven"], 20);  // t=0.05 (it connects) + 20 steps
  Trace trace(out / "trace.csv");
  EXPECT_NEAR(trace.rows().back().num("time"), 1.05, 1e-9);  // the trace stops where it left
  EXPECT_LT(r.wall_s, 30.0);
}

TEST(EgoFaults, APluginThatStopsAnsweringTimesOut) {
  TempDir out;
  const auto r = run_with_plugin(kScenario, out, drive("hang", 10, out), {"--ego-timeout", "1"}, 1);
  expect_error_with_outputs(r, out, "ego timeout at t=0.550 s: no message from the plug-in for 1 s");
  EXPECT_EQ(r.result["ego_plugin"]["end"], "timeout");
  EXPECT_LT(r.wall_s, 30.0);
}

TEST(EgoFaults, APluginThatClosesBeforeTheEndIsAnError) {
  TempDir out;
  const auto r = run_with_plugin(kScenario, out, drive("close", 5, out));
  expect_error_with_outputs(r, out, "ego disconnected at t=0.300 s: the plug-in closed the connection");
  EXPECT_EQ(r.plugin_exit, 0) << r.plugin_output;
}

TEST(EgoFaults, MalformedMessagesGetAnErrorStatusAndAClosedConnection) {
  for (const std::string kase : {"zero", "huge", "truncated", "wrongtype"}) {
    SCOPED_TRACE(kase);
    TempDir out;
    const auto r = run_with_plugin(
        kScenario, out, python_client("raw.py", {"{port}", kase, (out / "raw.json").string()}));
    expect_error_with_outputs(r, out, "ego protocol error at t=0.050 s");
    const auto raw = read_json(out / "raw.json");
    EXPECT_EQ(raw["status"]["result"], 0xFF) << raw.dump();
    EXPECT_FALSE(raw["status"]["text"].get<std::string>().empty());
    EXPECT_EQ(raw["closed"], true);
  }
}

TEST(EgoFaults, APortInUseFailsTheRunBeforeSumoStarts) {
  TempDir out;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(fd, 1), 0);
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len), 0);
  const auto r = run_cli({"run", kScenario, "--out", out.path().string(), "-q", "--ego-port",
                          std::to_string(ntohs(a.sin_port))});
  ::close(fd);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto result = read_json(out / "result.json");
  EXPECT_NE(result["reason"].get<std::string>().find("cannot listen for the ego plug-in"), std::string::npos);
  EXPECT_EQ(result["sumo_version"], "");  // SUMO never started
}

TEST(EgoFaults, CtrlCWhileWaitingForThePluginEndsTheRun) {
  TempDir out;
  Child orchestrator({ORCH_BINARY, "run", kScenario, "--out", out.path().string(), "-q", "--ego-port",
                      std::to_string(free_port())},
                     out / "orchestrator.out");
  std::this_thread::sleep_for(std::chrono::seconds(3));  // SUMO is up, the server waits
  orchestrator.signal(SIGINT);
  EXPECT_EQ(orchestrator.wait(std::chrono::seconds(20)), 2);
  const auto result = read_json(out / "result.json");
  EXPECT_NE(result["reason"].get<std::string>().find("interrupted"), std::string::npos) << result["reason"];
}

TEST(EgoFaults, EgoOptionsAreCheckedByTheCommandLine) {
  TempDir out;
  const auto bad_port = run_cli({"run", kScenario, "--out", out.path().string(), "--ego-port", "70000"});
  EXPECT_NE(bad_port.exit_code, 0);
  EXPECT_NE(bad_port.output.find("--ego-port"), std::string::npos) << bad_port.output;
  const auto bad_address = run_cli({"run", kScenario, "--out", out.path().string(), "-q", "--ego-port", "0",
                                    "--ego-address", "not-an-ip", "--ego-wait", "1"});
  EXPECT_EQ(bad_address.exit_code, 2);
  EXPECT_NE(read_json(out / "result.json")["reason"].get<std::string>().find("not an IP address"), std::string::npos);
}
