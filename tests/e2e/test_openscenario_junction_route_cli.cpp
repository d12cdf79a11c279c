// OpenSCENARIO routes through a real junction road with the CLI on SUMO
// (scenarios/openscenario/junction_route.xosc on SUMO's own OpenDRIVE output of a T
// junction): the routed scripted car turns right, the one without a route goes straight on
// and stops at the dead end, the SUMO-driven ego turns left along the route its
// AssignRouteAction gave SUMO. Both backends, the same trace bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

const std::string kSample = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/junction_route.xosc";

// Each actor's SUMO edges in the order it drove them (junction-internal lanes left out).
std::map<std::string, std::vector<std::string>> edges_driven(const Trace& trace) {
  std::map<std::string, std::vector<std::string>> out;
  for (const auto& row : trace.rows()) {
    const std::string edge = row.str("edge");
    auto& seq = out[row.str("actor_id")];
    if (edge.empty() || edge[0] == ':') continue;
    if (seq.empty() || seq.back() != edge) seq.push_back(edge);
  }
  return out;
}

std::map<std::string, const Trace::Row*> last_rows(const Trace& trace) {
  std::map<std::string, const Trace::Row*> out;
  for (const auto& row : trace.rows()) out[row.str("actor_id")] = &row;
  return out;
}

TEST(OpenScenarioJunctionRouteCli, RoutesTurnAtTheJunctionOnBothBackends) {
  TempDir libsumo_out, traci_out;
  const auto r = run_cli({"run", kSample, "--out", libsumo_out.path().string(), "-q"});
  const auto result = read_json(libsumo_out / "result.json");
  ASSERT_EQ(result["verdict"], "success") << result["reason"] << "\n" << r.output;
  const Trace trace(libsumo_out / "trace.csv");
  const auto edges = edges_driven(trace);
  // Road 45 runs W -> C; 41 C -> S (a right turn), 40 C -> E (straight on); 44 S -> C, 42 C -> W.
  EXPECT_EQ(edges.at("Turner"), (std::vector<std::string>{"-45", "-41"}));
  EXPECT_EQ(edges.at("Straight"), (std::vector<std::string>{"-45", "-40"}));
  EXPECT_EQ(edges.at("Ego"), (std::vector<std::string>{"-44", "-42"}));
  const auto last = last_rows(trace);
  // At 30 s: Turner heads south, Straight stands at road 40's end (x = 200), the ego (SUMO
  // drove it) heads west, still in SUMO (a one-edge route would have ended at C).
  EXPECT_NEAR(last.at("Turner")->num("heading"), -1.5708, 0.01);
  EXPECT_LT(last.at("Turner")->num("y"), -50.0);
  EXPECT_NEAR(last.at("Straight")->num("x"), 200.0, 3.0);
  EXPECT_NEAR(last.at("Straight")->num("speed"), 0.0, 1e-9);
  EXPECT_NEAR(last.at("Ego")->num("time"), last.at("Turner")->num("time"), 1e-9);
  EXPECT_NEAR(std::abs(last.at("Ego")->num("heading")), 3.1416, 0.01);
  EXPECT_LT(last.at("Ego")->num("x"), -30.0);
  EXPECT_EQ(last.at("Ego")->str("driver"), "sumo");

  const auto t = run_cli({"run", kSample, "--backend", "traci", "--out", traci_out.path().string(), "-q"});
  ASSERT_EQ(read_json(traci_out / "result.json")["verdict"], "success") << t.output;
  EXPECT_TRUE(slurp(libsumo_out / "trace.csv") == slurp(traci_out / "trace.csv")) << "libsumo and libtraci traces differ";
}

}  // namespace
