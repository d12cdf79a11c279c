// The SUMO backends end to end: libsumo and traci give the same bytes, sumo-gui runs, a
// running SUMO can be joined, and SUMO's failures (a broken net, an impossible route, a
// SUMO that dies or hangs) end the run as an error with SUMO's own words, no process left.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "support/cli_runner.hpp"
#include "support/process_tree.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

std::string cut_in() { return source_path("scenarios/highway_cut_in.json"); }

// A copy of the shipped highway map whose net SUMO refuses (valid XML, so the orchestrator's
// own reading of the lanes still works: the error is SUMO's).
std::filesystem::path broken_map(const TempDir& dir) {
  const auto maps = dir / "maps";
  std::filesystem::create_directories(maps / "highway");
  for (const char* f : {"map.json", "highway.waypoint.json", "highway.net.xml"})
    std::filesystem::copy_file(source_path(std::string("sumo_nets/highway/") + f), maps / "highway" / f);
  std::string net = slurp(maps / "highway" / "highway.net.xml");
  net.insert(net.rfind("</net>"), "    <junction id=\"broken\" type=\"no_such_type\"/>\n");
  std::ofstream(maps / "highway" / "highway.net.xml") << net;
  return maps;
}

std::string verdict_of(const TempDir& out) { return read_json(out / "result.json")["verdict"]; }
std::string reason_of(const TempDir& out) { return read_json(out / "result.json")["reason"]; }

}  // namespace

TEST(BackendsCli, LibsumoAndTraciGiveByteIdenticalOutputsWithTraffic) {
  TempDir a, b;
  const std::vector<std::string> opts{"--traffic", "dense", "--seed", "3", "--max-time", "20", "--trace-background"};
  auto with = [&](const char* backend) {
    auto o = opts;
    o.insert(o.end(), {"--backend", backend});
    return o;
  };
  ASSERT_EQ(run_scenario(cut_in(), a, with("libsumo")).exit_code, 1);
  ASSERT_EQ(run_scenario(cut_in(), b, with("traci")).exit_code, 1);
  EXPECT_EQ(read_json(a / "result.json")["backend"], "libsumo");
  EXPECT_EQ(read_json(b / "result.json")["backend"], "traci");
  EXPECT_EQ(read_json(a / "result.json")["metrics"], read_json(b / "result.json")["metrics"]);
  for (const char* file : {"trace.csv", "counts.csv", "background.csv", "metrics.csv"}) {
    SCOPED_TRACE(file);
    const std::string bytes = slurp(a / file);
    EXPECT_GT(bytes.size(), 1000u);
    EXPECT_TRUE(bytes == slurp(b / file));
  }
}

TEST(BackendsCli, BrokenNetIsAnErrorWithSumosMessageOnBothBackends) {
  for (const char* backend : {"libsumo", "traci"}) {
    SCOPED_TRACE(backend);
    TempDir out;
    const auto maps = broken_map(out);
    const auto r = run_scenario(cut_in(), out, {"--maps", maps.string(), "--backend", backend});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(verdict_of(out), "error");
    // SUMO's own words, not a bare "Process Error".
    EXPECT_NE(reason_of(out).find("in definition of junction 'broken' is not a valid node type"),
              std::string::npos)
        << reason_of(out);
  }
}

TEST(BackendsCli, RouteSumoCannotBuildMidRunIsAnErrorAndTheTraceIsKept) {
  for (const char* backend : {"libsumo", "traci"}) {
    SCOPED_TRACE(backend);
    TempDir out;
    // The two carriageways are not connected: at t = 5 s SUMO cannot route this car.
    const auto traffic = out.write(
        "unroutable.rou.xml",
        "<routes>\n  <trip id=\"bad\" depart=\"5\" from=\"Waypoint03+Waypoint02+Waypoint01#0\" "
        "to=\"Waypoint03R+Waypoint02R+Waypoint01R#3\"/>\n</routes>\n");
    const auto r = run_scenario(cut_in(), out, {"--traffic", traffic.string(), "--backend", backend});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(verdict_of(out), "error");
    EXPECT_NE(reason_of(out).find("Vehicle 'bad' has no valid route"), std::string::npos) << reason_of(out);
    Trace trace(out / "trace.csv");
    ASSERT_FALSE(trace.rows().empty());
    EXPECT_NEAR(trace.rows().back().num("time"), 5.0, 0.051);  // every step up to the error, flushed
    EXPECT_EQ(static_cast<long long>(trace.rows().size()), read_json(out / "result.json")["trace_rows"].get<long long>());
  }
}

TEST(BackendsCli, KilledSumoIsAnErrorWithinSecondsAndNoSumoIsLeft) {
  TempDir out;
  // Real time keeps the run going long enough to kill its SUMO in the middle.
  const pid_t orch = spawn_cli({"run", cut_in(), "--out", out.path().string(), "-q", "--backend", "traci",
                                "--traffic", "light", "--realtime", "1"},
                               out / "console.txt");
  const auto sumo = find_child(orch, "sumo", 30);
  ASSERT_TRUE(sumo.has_value()) << slurp(out / "console.txt");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ::kill(*sumo, SIGKILL);
  const auto t0 = std::chrono::steady_clock::now();
  const auto code = wait_for_exit(orch, 20);
  ASSERT_TRUE(code.has_value()) << "the orchestrator did not end";
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  EXPECT_EQ(*code, 2);
  EXPECT_EQ(verdict_of(out), "error");
  EXPECT_NE(reason_of(out).find("SUMO was killed by signal 9"), std::string::npos) << reason_of(out);
  EXPECT_FALSE(process_alive(*sumo));
  EXPECT_GT(Trace(out / "trace.csv").rows().size(), 10u);  // what ran before is kept
}

TEST(BackendsCli, HungSumoIsAnErrorAfterTheReplyTimeoutAndIsStopped) {
  TempDir out;
  const pid_t orch = spawn_cli({"run", cut_in(), "--out", out.path().string(), "-q", "--backend", "traci",
                                "--realtime", "1", "--sumo-timeout", "2"},
                               out / "console.txt");
  const auto sumo = find_child(orch, "sumo", 30);
  ASSERT_TRUE(sumo.has_value()) << slurp(out / "console.txt");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ::kill(*sumo, SIGSTOP);  // alive, holding the connection, answering nothing
  const auto t0 = std::chrono::steady_clock::now();
  const auto code = wait_for_exit(orch, 30);
  ASSERT_TRUE(code.has_value()) << "the orchestrator waited forever";
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 8.0);
  EXPECT_EQ(*code, 2);
  EXPECT_NE(reason_of(out).find("did not answer within 2 s"), std::string::npos) << reason_of(out);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_FALSE(process_alive(*sumo));
}

TEST(BackendsCli, KilledOrchestratorTakesItsSumoAlong) {
  TempDir out;
  const pid_t orch = spawn_cli({"run", cut_in(), "--out", out.path().string(), "-q", "--backend", "traci",
                                "--realtime", "1"},
                               out / "console.txt");
  const auto sumo = find_child(orch, "sumo", 30);
  ASSERT_TRUE(sumo.has_value()) << slurp(out / "console.txt");
  ::kill(orch, SIGKILL);
  wait_for_exit(orch, 5);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (process_alive(*sumo) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(process_alive(*sumo));
}

TEST(BackendsCli, GuiRunUnderXvfbEndsWithAVerdict) {
  TempDir out;
  const std::string cmd = "xvfb-run -a " + shell_quote(ORCH_BINARY) + " run " + shell_quote(cut_in()) + " --out " +
                          shell_quote(out.path().string()) + " -q --gui --traffic light 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) output.append(buf, n);
  const int status = ::pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  const auto result = read_json(out / "result.json");
  EXPECT_EQ(result["verdict"], "success") << output;
  EXPECT_EQ(result["backend"], "traci");
  EXPECT_GT(Trace(out / "counts.csv").rows().back().integer("background_vehicles"), 0);
}

TEST(BackendsCli, ConnectJoinsARunningSumoAndGivesTheSameTrace) {
  TempDir joined, own;
  // A port below the kernel's ephemeral range (as the orchestrator picks for its own SUMO).
  const int port = 20000 + static_cast<int>(::getpid() % 5000);
  const pid_t sumo = ::fork();
  if (sumo == 0) {
    const std::string net = source_path("sumo_nets/highway/highway.net.xml");
    const std::string port_text = std::to_string(port);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    ::dup2(null_fd, STDOUT_FILENO);
    ::dup2(null_fd, STDERR_FILENO);
    ::execlp("sumo", "sumo", "-n", net.c_str(), "--remote-port", port_text.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto r = run_scenario(cut_in(), joined, {"--connect", "127.0.0.1:" + std::to_string(port), "--traffic", "light"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(wait_for_exit(sumo, 10).has_value()) << "the joined SUMO did not end with the run";
  ASSERT_EQ(run_scenario(cut_in(), own, {"--traffic", "light"}).exit_code, 0);
  // The joined SUMO loaded the run's own net, traffic and settings.
  EXPECT_EQ(slurp(joined / "trace.csv"), slurp(own / "trace.csv"));
  EXPECT_EQ(read_json(joined / "result.json")["backend"], "traci");
}

TEST(BackendsCli, GuiOrConnectWithLibsumoIsRefused) {
  TempDir out;
  const auto r = run_scenario(cut_in(), out, {"--backend", "libsumo", "--gui"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--backend traci"), std::string::npos) << r.output;
}

TEST(BackendsCli, RealtimeMakesTheRunTakeAtLeastItsSimulatedTime) {
  TempDir out;
  ASSERT_EQ(run_scenario(cut_in(), out, {"--max-time", "2", "--realtime", "2"}).exit_code, 1);
  const auto result = read_json(out / "result.json");
  // 2 s simulated at twice real time: at least 1 s of wall-clock time (a lower bound only).
  EXPECT_GE(result["wall_time_s"].get<double>(), 1.0);
}
