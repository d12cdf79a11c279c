// OpenSCENARIO parameter variations end to end: `validate`, `sample` and `batch` of
// `*_variation.xosc` files with real child runs on SUMO, checked through the files a nightly
// job reads and through the runs' own traces (the values really reached the scenario).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"
#include "support/xosc_variation.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

const std::string kLeadBrake = source_path("scenarios/openscenario/nightly/lead_brake.xosc");

// A deterministic variation of the shipped lead_brake.xosc (by absolute path).
std::string variation(const std::string& body) { return orch::test::deterministic_variation(body, kLeadBrake); }

std::string fmt_param(const std::string& name, double value) {
  return "--param " + name + "=" + nlohmann::json(value).dump();
}

// The strongest deceleration of `entity` in a run's trace (m/s^2, positive).
double peak_deceleration(const fs::path& trace_file, const std::string& entity) {
  Trace trace(trace_file);
  double peak = 0;
  for (const auto& row : trace.rows())
    if (row.str("actor_id") == entity) peak = std::max(peak, -row.num("accel"));
  return peak;
}

std::map<double, nlohmann::json> executions_by_decel(const fs::path& out) {
  std::map<double, nlohmann::json> by;
  for (const auto& e : fs::directory_iterator(out / "executions")) {
    const auto j = read_json(e.path());
    by[j["trace"]["sampled_values"]["param"]["Decel_mps2"].get<double>()] = j;
  }
  return by;
}

}  // namespace

TEST(BatchVariationCli, ValidateChecksTheShippedVariationsAndNamesErrors) {
  const auto ok = run_cli({"validate", source_path("scenarios/openscenario/nightly/lead_brake_variation.xosc"),
                           source_path("scenarios/openscenario/nightly/lead_brake_grid_variation.xosc")});
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("2 valid, 0 invalid"), std::string::npos) << ok.output;

  TempDir dir;
  const auto bad = dir.write("bad_variation.xosc", variation(R"(
      <DeterministicSingleParameterDistribution parameterName="Decel_mps">
        <DistributionSet><Element value="3"/></DistributionSet>
      </DeterministicSingleParameterDistribution>)"));
  const auto r = run_cli({"validate", bad.string()});
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(bad.string() + ":8: error: /OpenSCENARIO/ParameterValueDistribution/Deterministic/"
                          "DeterministicSingleParameterDistribution: the scenario"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean \"Decel_mps2\""), std::string::npos) << r.output;
}

TEST(BatchVariationCli, BatchRunsEveryCombinationWithItsValuesOnSumo) {
  TempDir in, out_root;
  const auto file = in.write("brake_variation.xosc", variation(R"(
      <DeterministicSingleParameterDistribution parameterName="Decel_mps2">
        <DistributionSet><Element value="3"/><Element value="9"/></DistributionSet>
      </DeterministicSingleParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="BrakeTime_s">
        <DistributionSet><Element value="1"/></DistributionSet>
      </DeterministicSingleParameterDistribution>)"));
  const fs::path out = out_root / "b";
  const auto r = run_cli({"batch", file.string(), "--out", out.string(), "--jobs", "2"});
  ASSERT_LE(r.exit_code, 1) << r.output;
  const auto summary = read_json(out / "summary.json");
  EXPECT_EQ(summary["totals"]["runs"], 2);
  EXPECT_EQ(summary["totals"]["error"], 0) << r.output;
  const auto by = executions_by_decel(out);
  ASSERT_EQ(by.size(), 2u);
  for (const auto& [decel, execution] : by) {
    const auto& impl = execution["trace"]["implementation"];
    EXPECT_EQ(impl["scenario_file"], fs::path(kLeadBrake).lexically_normal().string());
    EXPECT_NE(impl["command"].get<std::string>().find(fmt_param("Decel_mps2", decel)), std::string::npos)
        << impl["command"];
    EXPECT_EQ(execution["trace"]["sampled_values"]["param"]["BrakeTime_s"], 1.0);
    EXPECT_EQ(execution["trace"]["parameter_file"], file.string());
    // The lead brakes as hard as the set says (the rate of its SpeedAction), so the value
    // reached the scenario: SUMO's acceleration of the scripted lead, from the trace.
    const fs::path run_dir = out / execution["outputs"]["run_dir"].get<std::string>();
    EXPECT_NEAR(peak_deceleration(run_dir / "trace.csv", "LeadVehicle"), decel, 0.05) << decel;
    EXPECT_NE(slurp(run_dir / "run.log").find("--param Decel_mps2="), std::string::npos);
  }
  std::set<double> summarised;
  for (const auto& run : summary["runs"]) summarised.insert(run["sampled_values"]["param"]["Decel_mps2"].get<double>());
  EXPECT_EQ(summarised, (std::set<double>{3.0, 9.0}));
}

TEST(BatchVariationCli, SampleDrawsASubsetThatBatchRunsShardByShard) {
  TempDir in, out_root;
  const auto file = in.write("grid_variation.xosc", variation(R"(
      <DeterministicSingleParameterDistribution parameterName="Decel_mps2">
        <DistributionRange stepWidth="1"><Range lowerLimit="3" upperLimit="9"/></DistributionRange>
      </DeterministicSingleParameterDistribution>
      <DeterministicMultiParameterDistribution><ValueSetDistribution>
        <ParameterValueSet><ParameterAssignment parameterRef="BrakeTime_s" value="1"/><ParameterAssignment parameterRef="Gap_m" value="20"/></ParameterValueSet>
        <ParameterValueSet><ParameterAssignment parameterRef="BrakeTime_s" value="2"/><ParameterAssignment parameterRef="Gap_m" value="30"/></ParameterValueSet>
      </ValueSetDistribution></DeterministicMultiParameterDistribution>)"));
  // 7 x 2 = 14 combinations; two of them, seeded.
  const auto s = run_cli({"sample", file.string(), "--count", "2", "--seed", "4", "--max-time", "40"});
  ASSERT_EQ(s.exit_code, 0) << s.output;
  const fs::path params = in / "grid_variation_parameters.json";
  const auto sets = read_json(params);
  ASSERT_EQ(sets["parameters"].size(), 2u);
  std::map<std::string, double> decel_of_set;
  for (auto it = sets["parameters"].begin(); it != sets["parameters"].end(); ++it) {
    const long long seed = it.value()["seed"].get<long long>();
    EXPECT_GE(seed, 1);
    EXPECT_LE(seed, 14);
    EXPECT_EQ(it.value()["sumo_config"]["max_time"], 40.0);
    EXPECT_EQ(it.value()["sumo_config"]["map"], "motorway_3_lanes");
    decel_of_set[it.key()] = it.value()["sampled_values"]["param"]["Decel_mps2"].get<double>();
  }
  const auto shard1 = run_cli({"batch", params.string(), "--out", (out_root / "s1").string(), "--shard", "1/2"});
  const auto shard2 = run_cli({"batch", params.string(), "--out", (out_root / "s2").string(), "--shard", "2/2"});
  ASSERT_LE(shard1.exit_code, 1) << shard1.output;
  ASSERT_LE(shard2.exit_code, 1) << shard2.output;
  std::map<std::string, double> ran;
  for (const char* shard : {"s1", "s2"}) {
    const auto by = executions_by_decel(out_root / shard);
    EXPECT_EQ(by.size(), 1u) << shard;
    for (const auto& [decel, execution] : by) {
      ran[execution["parameter_uuid"]] = decel;
      EXPECT_EQ(execution["trace"]["parameter_file"], params.string());
      EXPECT_NE(execution["trace"]["implementation"]["command"].get<std::string>().find("--max-time 40"), std::string::npos);
    }
  }
  EXPECT_EQ(ran, decel_of_set);

  // Sampling again with the same seed adds two other combinations, never one twice.
  const auto again = run_cli({"sample", file.string(), "--count", "2", "--seed", "4"});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  std::set<long long> seeds;
  const auto resampled = read_json(params);
  for (const auto& set : resampled["parameters"]) seeds.insert(set["seed"].get<long long>());
  EXPECT_EQ(seeds.size(), 4u);
}
