// The orchestrator's following metrics of a SUMO-driven ego against SUMO's own SSM device
// (`run --ssm`), on both backends: a car-following scenario (the lead brakes to a stop) and
// a cut-in. Over the steps where both define a value, the minimum TTC (SUMO: TTC of the
// conflicts where the ego follows its foe), THW (SUMO: TGAP) and gap (SUMO: SGAP) agree
// within 5 % or 0.1 s / 0.2 m. docs/evaluation.md states where the two differ by definition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <pugixml.hpp>
#include <sstream>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

// SUMO's encounter type "following, the ego is the follower" (MSDevice_SSM's
// ENCOUNTER_TYPE_FOLLOWING_FOLLOWER): the foe is the ego's leader, as for our `ttc`.
constexpr int kEgoFollows = 2;

// A per-step series keyed by time in ms (SUMO writes times with two decimals).
using Series = std::map<long, double>;
long key_of(double t) { return std::lround(t * 1000); }

std::vector<std::string> words(const pugi::xml_node& n) {
  std::istringstream in(n.attribute("values").as_string());
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

struct SsmLog {
  Series ttc;   // the ego's smallest TTC against a foe it follows, per step
  Series sgap;  // space gap to the leader
  Series tgap;  // time gap to the leader
  int conflicts = 0;
};

// SUMO's device.ssm output with trajectories (run/ssm_device.cpp's options). SUMO labels a
// step's values with the time the step began (the positions are those after it): each is
// filed under that time + `step`, the time the orchestrator's row of the same step has.
SsmLog read_ssm(const std::filesystem::path& file, const std::string& ego, double step) {
  pugi::xml_document doc;
  const auto parsed = doc.load_file(file.c_str());
  if (!parsed) throw std::runtime_error(file.string() + ": " + parsed.description());
  SsmLog log;
  const pugi::xml_node root = doc.child("SSMLog");
  for (const auto& conflict : root.children("conflict")) {
    if (std::string(conflict.attribute("ego").as_string()) != ego) continue;
    ++log.conflicts;
    const auto times = words(conflict.child("timeSpan"));
    const auto types = words(conflict.child("typeSpan"));
    const auto ttcs = words(conflict.child("TTCSpan"));
    for (std::size_t i = 0; i < times.size() && i < types.size() && i < ttcs.size(); ++i) {
      if (ttcs[i] == "NA" || std::stoi(types[i]) != kEgoFollows) continue;
      const long k = key_of(std::stod(times[i]) + step);
      const double v = std::stod(ttcs[i]);
      const auto it = log.ttc.find(k);
      log.ttc[k] = it == log.ttc.end() ? v : std::min(it->second, v);
    }
  }
  for (const auto& global : root.children("globalMeasures")) {
    if (std::string(global.attribute("ego").as_string()) != ego) continue;
    const auto times = words(global.child("timeSpan"));
    const auto read = [&](const char* span, Series& into) {
      const auto values = words(global.child(span));
      for (std::size_t i = 0; i < times.size() && i < values.size(); ++i)
        if (values[i] != "NA") into[key_of(std::stod(times[i]) + step)] = std::stod(values[i]);
    };
    read("SGAPSpan", log.sgap);
    read("TGAPSpan", log.tgap);
  }
  return log;
}

// One column of metrics.csv for an actor, the steps where it has a value.
Series metric_series(const std::filesystem::path& csv, int actor, const std::string& column) {
  const Trace metrics(csv);
  Series out;
  for (const auto& row : metrics.actor(actor))
    if (!row.str(column).empty()) out[key_of(row.num("time"))] = row.num(column);
  return out;
}

struct Minima {
  double ours = INFINITY, sumo = INFINITY;
  double ours_time = 0, sumo_time = 0;
  int common_steps = 0;
};

// The smallest value of each series over the steps both define.
Minima minima_where_both_define(const Series& ours, const Series& sumo) {
  Minima m;
  for (const auto& [k, v] : ours) {
    const auto s = sumo.find(k);
    if (s == sumo.end()) continue;
    ++m.common_steps;
    const double t = static_cast<double>(k) / 1000.0;
    if (v < m.ours) m.ours = v, m.ours_time = t;
    if (s->second < m.sumo) m.sumo = s->second, m.sumo_time = t;
  }
  return m;
}

void expect_agree(const char* what, const Minima& m, double absolute, int min_common_steps) {
  ASSERT_GE(m.common_steps, min_common_steps) << what << ": too few steps where both define it";
  const double tolerance = std::max(0.05 * std::abs(m.sumo), absolute);
  EXPECT_NEAR(m.ours, m.sumo, tolerance) << what << ": ours " << m.ours << " at t=" << m.ours_time << " s, SUMO's "
                                         << m.sumo << " at t=" << m.sumo_time << " s, over " << m.common_steps
                                         << " common steps";
}

struct Case {
  const char* scenario;
  const char* backend;
  int min_ttc_steps;  // steps where both must define a TTC (closing in on the leader)
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string s = std::filesystem::path(info.param.scenario).stem().string() + "_" + info.param.backend;
  std::replace_if(s.begin(), s.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return s;
}

}  // namespace

class SsmComparison : public ::testing::TestWithParam<Case> {};

TEST_P(SsmComparison, MinimumTtcThwAndGapAgreeWithSumosSsmDevice) {
  const Case& c = GetParam();
  TempDir out;
  const auto r = run_scenario(source_path(c.scenario), out, {"--ssm", "--backend", c.backend, "--no-report"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(out / "result.json");
  const std::string args = result["sumo_args"].dump();
  EXPECT_NE(args.find("--device.ssm.explicit"), std::string::npos) << args;
  ASSERT_TRUE(std::filesystem::exists(out / "ssm.xml")) << "SUMO wrote no ssm.xml";

  std::string ego;
  for (const auto& a : result["actors"])
    if (a["ego"].get<bool>()) ego = a["sumo_id"].get<std::string>();
  ASSERT_FALSE(ego.empty()) << result["actors"].dump();
  const SsmLog ssm = read_ssm(out / "ssm.xml", ego, result["step"].get<double>());
  EXPECT_GE(ssm.conflicts, 1);

  const auto csv = out / "metrics.csv";
  expect_agree("TTC", minima_where_both_define(metric_series(csv, 0, "ttc"), ssm.ttc), 0.1, c.min_ttc_steps);
  expect_agree("THW vs TGAP", minima_where_both_define(metric_series(csv, 0, "thw"), ssm.tgap), 0.1, 100);
  expect_agree("gap vs SGAP", minima_where_both_define(metric_series(csv, 0, "gap"), ssm.sgap), 0.2, 100);
}

INSTANTIATE_TEST_SUITE_P(BothBackends, SsmComparison,
                         ::testing::Values(Case{"scenarios/alks_lead_brake.json", "libsumo", 20},
                                           Case{"scenarios/alks_lead_brake.json", "traci", 20},
                                           Case{"scenarios/highway_cut_in.json", "libsumo", 20},
                                           Case{"scenarios/highway_cut_in.json", "traci", 20}),
                         case_name);

TEST(SsmDevice, AnEgoDrivenByAPlugInGetsNone) {
  // Without SUMO driving the ego there is nothing of SUMO's to compare: no device, a note.
  TempDir out;
  const auto r = run_scenario(source_path("scenarios/alks_lead_brake.json"), out,
                              {"--ssm", "--ego-port", "0", "--ego-wait", "0.2", "--no-report"});
  EXPECT_FALSE(std::filesystem::exists(out / "ssm.xml"));
  EXPECT_NE(slurp(out / "run.log").find("--ssm: the ego is driven by the plug-in"), std::string::npos)
      << slurp(out / "run.log");
}
