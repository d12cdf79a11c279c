// `orchestrator run` of an OpenSCENARIO file with TrafficActions, on real SUMO, with the real
// CLI: what the swarm, source and sink did is in result.json (storyboard_traffic), their
// vehicles are in traffic_actions.csv and in the report's data, the same seed gives the same
// bytes, and a sink also removes the --traffic background vehicles that reach it.
// tests/data/openscenario/traffic_actions.xosc: a swarm of 6 around the ego (s 400 -> 720 at
// 8 m/s), a source of 0.5 vehicles/s at s = 300 stopped at 20 s, a sink of 20 m at s = 700.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kTrafficActions = std::string(ORCH_SOURCE_DIR) + "/tests/data/openscenario/traffic_actions.xosc";
constexpr double kSinkX = 700, kSinkY = -1.75, kSinkRadius = 20;

// The run of the file, once for the tests that only read it.
const std::filesystem::path& traffic_run() {
  static TempDir root;
  static const std::filesystem::path out = [] {
    const auto r = run_cli({"run", kTrafficActions, "--out", (root / "run").string(), "-q"});
    if (r.exit_code != 0) throw std::runtime_error(r.output);
    return root / "run";
  }();
  return out;
}

const nlohmann::json& action(const nlohmann::json& traffic, const std::string& label) {
  for (const auto& a : traffic["actions"])
    if (a["label"] == label) return a;
  throw std::runtime_error("no traffic action " + label + " in " + traffic.dump());
}

}  // namespace

TEST(OpenScenarioTrafficCli, ResultJsonSaysWhatEachTrafficActionDid) {
  const auto result = read_json(traffic_run() / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"];
  const auto& traffic = result["storyboard_traffic"];
  ASSERT_TRUE(traffic.is_object()) << result.dump(1);
  // Every action, in the order they started, with its kind, name and time span.
  std::vector<std::string> order;
  for (const auto& a : traffic["actions"]) order.push_back(a["kind"].get<std::string>() + " " + a["name"].get<std::string>());
  EXPECT_EQ(order, (std::vector<std::string>{"swarm Crowd", "source Inflow", "sink Outflow"}));
  const auto& swarm = action(traffic, "Crowd");
  const auto& source = action(traffic, "Inflow");
  const auto& sink = action(traffic, "Outflow");
  EXPECT_EQ(swarm["started"], 0.0);
  EXPECT_TRUE(swarm["stopped"].is_null());  // ran to the end
  EXPECT_NEAR(source["stopped"].get<double>(), 20.0, 0.051);  // the TrafficStopAction
  EXPECT_EQ(swarm["vehicles"], "traffic1.N");
  EXPECT_EQ(source["vehicles"], "traffic2.N");
  // Every vehicle of a swarm or source is accounted for.
  for (const auto* a : {&swarm, &source})
    EXPECT_EQ((*a)["spawned"].get<int>(), (*a)["active_at_end"].get<int>() + (*a)["removed"].get<int>() +
                                               (*a)["left"].get<int>() + (*a)["not_inserted"].get<int>())
        << a->dump();
  // The swarm keeps 6 and replaced the ones it or the sink removed.
  EXPECT_LE(swarm["active_at_end"].get<int>(), 6);
  EXPECT_GT(swarm["spawned"].get<int>(), 6);
  EXPECT_GT(swarm["removed"].get<int>(), 0);
  // The source: one every 2 s from 0 until its stop at 20 s (at most 10), every one of them
  // taken by the sink 400 m on (at 20 m/s the last one reaches it at 38 s, before the end).
  EXPECT_LE(source["spawned"].get<int>(), 10);
  EXPECT_GE(source["spawned"].get<int>(), 8);
  EXPECT_EQ(source["active_at_end"], 0);
  EXPECT_EQ(source["removed"].get<int>() + source["not_inserted"].get<int>(), source["spawned"].get<int>());
  // The sink spawns none; what it removed is the source's and part of the swarm's (no background here).
  EXPECT_EQ(sink["spawned"], 0);
  EXPECT_EQ(sink["removed_background"], 0);
  EXPECT_GE(sink["removed"].get<int>(), source["removed"].get<int>());
  EXPECT_LE(sink["removed"].get<int>(), source["removed"].get<int>() + swarm["removed"].get<int>());
  // The totals are the actions' (a vehicle the sink removed counted once).
  EXPECT_EQ(traffic["spawned"].get<int>(), swarm["spawned"].get<int>() + source["spawned"].get<int>());
  EXPECT_EQ(traffic["removed"].get<int>(), swarm["removed"].get<int>() + source["removed"].get<int>());
  EXPECT_EQ(traffic["active_at_end"].get<int>(), swarm["active_at_end"].get<int>());
  // run.log says the same, per action.
  const std::string log = slurp(traffic_run() / "run.log");
  EXPECT_NE(log.find("Inflow (source, 0.00 s to 20.00 s): " + std::to_string(source["spawned"].get<int>()) +
                     " vehicles spawned, " + std::to_string(source["removed"].get<int>()) + " removed"),
            std::string::npos)
      << log;
}

TEST(OpenScenarioTrafficCli, TheTrafficVehiclesAreTracedAndCarriedIntoTheReport) {
  const auto result = read_json(traffic_run() / "result.json");
  const auto& traffic = result["storyboard_traffic"];
  const Trace vehicles(traffic_run() / "traffic_actions.csv");
  EXPECT_EQ(vehicles.header(), "time,vehicle_id,x,y,heading,speed,length,width,traffic");
  // Per action: the vehicles traced (each row's traffic is the action's place in the list, its
  // id the action's "traffic<serial>.N"); every vehicle removed or gone was in SUMO, so traced.
  std::map<int, std::set<std::string>> ids;
  std::set<double> times;
  for (const auto& row : vehicles.rows()) {
    const int k = row.integer("traffic");
    ids[k].insert(row.str("vehicle_id"));
    times.insert(row.num("time"));
    EXPECT_EQ(row.str("vehicle_id").rfind("traffic" + std::to_string(k) + ".", 0), 0u) << row.str("vehicle_id");
  }
  ASSERT_EQ(ids.size(), 2u);  // the swarm's and the source's; a sink has none
  for (int k : {1, 2}) {
    const auto& a = traffic["actions"][k - 1];
    EXPECT_LE(ids[k].size(), static_cast<std::size_t>(a["spawned"].get<int>() - a["not_inserted"].get<int>())) << a.dump();
    EXPECT_GE(ids[k].size(), static_cast<std::size_t>(a["removed"].get<int>() + a["left"].get<int>())) << a.dump();
  }
  // The rows' times are trace.csv's (the storyboard's), so the replay lines them up.
  const Trace trace(traffic_run() / "trace.csv");
  std::set<double> trace_times;
  for (const auto& row : trace.rows()) trace_times.insert(row.num("time"));
  for (double t : times) EXPECT_TRUE(trace_times.count(t)) << t;
  // No source vehicle is traced past the sink's circle (a step's travel after entering it).
  for (const auto& row : vehicles.rows()) {
    if (row.integer("traffic") == 2) {
      EXPECT_LE(row.num("x"), kSinkX + kSinkRadius + 1.5) << row.str("vehicle_id");
    }
  }
  // The metrics measure them as they measure background traffic: the ego's leader and nearest
  // body are TrafficAction vehicles (the swarm drives in the ego's lane ahead of it).
  const Trace metrics(traffic_run() / "metrics.csv");
  std::size_t led_by_traffic = 0;
  for (const auto& row : metrics.rows())
    if (row.str("leader").rfind("traffic", 0) == 0) ++led_by_traffic;
  EXPECT_GT(led_by_traffic, 0u);
  EXPECT_TRUE(read_json(traffic_run() / "result.json")["ego_exposure"]["min_gap"].is_number());
  // trace.csv keeps the storyboard's entities only.
  for (const auto& row : trace.rows()) EXPECT_EQ(row.str("actor_id"), "Ego");
  // The report carries the vehicles for its replay, and the counts for its header.
  const std::string page = slurp(traffic_run() / "report.html");
  EXPECT_NE(page.find("\"traffic_actions\":{"), std::string::npos);
  EXPECT_NE(page.find("\"" + *ids[2].begin() + "\""), std::string::npos);
  EXPECT_NE(page.find("\"storyboard_traffic\":{"), std::string::npos);
}

TEST(OpenScenarioTrafficCli, TheSameSeedGivesTheSameTrafficBytes) {
  TempDir again;
  const auto r = run_cli({"run", kTrafficActions, "--out", (again / "run").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"traffic_actions.csv", "trace.csv", "metrics.csv", "counts.csv"})
    EXPECT_TRUE(slurp(traffic_run() / file) == slurp(again / "run" / file)) << file;
  EXPECT_EQ(read_json(traffic_run() / "result.json")["storyboard_traffic"],
            read_json(again / "run" / "result.json")["storyboard_traffic"]);
}

// The standard's sink takes every traffic participant in its radius: the background's too.
TEST(OpenScenarioTrafficCli, ASinkAlsoRemovesTheBackgroundVehiclesThatReachIt) {
  TempDir dir;
  const auto out = dir / "run";
  const auto r = run_cli({"run", kTrafficActions, "--out", out.string(), "-q", "--traffic", "dense",
                          "--trace-background"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  const auto& sink = action(result["storyboard_traffic"], "Outflow");
  EXPECT_GT(sink["removed_background"].get<int>(), 0) << sink.dump();
  EXPECT_EQ(result["storyboard_traffic"]["removed_background"], sink["removed_background"]);
  // A background vehicle traced inside the sink's circle is not traced two steps later (the
  // sink removes it in the step after it is seen there; SUMO's removal shows in the next).
  const Trace background(out / "background.csv");
  std::map<std::string, double> entered;  // vehicle -> first time inside
  std::map<std::string, double> last;     // vehicle -> last time traced
  for (const auto& row : background.rows()) {
    const std::string id = row.str("vehicle_id");
    EXPECT_EQ(id.rfind("traffic", 0), std::string::npos) << "TrafficAction vehicles are in traffic_actions.csv";
    last[id] = row.num("time");
    if (std::hypot(row.num("x") - kSinkX, row.num("y") - kSinkY) <= kSinkRadius && !entered.count(id))
      entered[id] = row.num("time");
  }
  ASSERT_FALSE(entered.empty());
  for (const auto& [id, t] : entered) EXPECT_LE(last[id], t + 0.1 + 1e-9) << id;
}
