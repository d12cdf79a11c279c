// The runs of OpenSCENARIO parameter variations: the deterministic product (size, order,
// seeded subsets), every stochastic distribution (seeded determinism, ranges, moments of
// many draws against the closed forms), and the parameter sets the batch runs.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "batch/variation_batch.hpp"
#include "batch/variation_sampling.hpp"
#include "core/errors.hpp"

namespace orch::batch {
namespace {

using namespace openscenario;

const std::string kNightly = std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/nightly/";
constexpr int kDraws = 20000;

struct Moments {
  double mean = 0;
  double variance = 0;
  double min = 1e300;
  double max = -1e300;
};

Moments moments_of(const StochasticKind& d, std::uint64_t seed = 11) {
  std::mt19937_64 engine(seed);
  std::vector<double> xs;
  for (int i = 0; i < kDraws; ++i) xs.push_back(draw_stochastic(d, engine));
  Moments m;
  for (double x : xs) {
    m.mean += x / kDraws;
    m.min = std::min(m.min, x);
    m.max = std::max(m.max, x);
  }
  for (double x : xs) m.variance += (x - m.mean) * (x - m.mean) / (kDraws - 1);
  return m;
}

Variation one_parameter(const std::string& type, StochasticKind d) {
  Variation v;
  v.file = "test_variation.xosc";
  v.stochastic = true;
  v.number_of_test_runs = 10;
  v.random_seed = 3;
  v.declared = {Parameter{"x", type, "0", false}};
  v.distributions = {StochasticParameter{"x", std::move(d), {}}};
  return v;
}

TEST(VariationProduct, SizeAndOrderOfTheShippedGrid) {
  const auto logical = load_variation_logical(kNightly + "lead_brake_grid_variation.xosc");
  const Variation& v = logical->variation;
  ASSERT_EQ(product_size(v), 16u);  // 4 decelerations x 2 speeds x 2 (gap, brake time) pairs
  const VariationValues first{{"Decel_mps2", "4"}, {"LeadSpeed_kph", "60"}, {"Gap_m", "25"}, {"BrakeTime_s", "4"}};
  EXPECT_EQ(product_values(v, 0), first);
  // The last factor varies fastest.
  const VariationValues second{{"Decel_mps2", "4"}, {"LeadSpeed_kph", "60"}, {"Gap_m", "8"}, {"BrakeTime_s", "6"}};
  EXPECT_EQ(product_values(v, 1), second);
  const VariationValues last{{"Decel_mps2", "10"}, {"LeadSpeed_kph", "80"}, {"Gap_m", "8"}, {"BrakeTime_s", "6"}};
  EXPECT_EQ(product_values(v, 15), last);
  std::set<VariationValues> all;
  for (std::uint64_t i = 0; i < 16; ++i) all.insert(product_values(v, i));
  EXPECT_EQ(all.size(), 16u);
}

TEST(VariationProduct, SeededSubsetIsDistinctRepeatableAndSkipsTaken) {
  const auto a = seeded_subset(1000, 50, 7, {});
  EXPECT_EQ(a, seeded_subset(1000, 50, 7, {}));
  EXPECT_NE(a, seeded_subset(1000, 50, 8, {}));
  EXPECT_EQ(std::set<std::uint64_t>(a.begin(), a.end()).size(), 50u);
  for (auto i : a) EXPECT_LT(i, 1000u);
  const std::set<std::uint64_t> taken(a.begin(), a.end());
  for (auto i : seeded_subset(1000, 950, 9, taken)) EXPECT_FALSE(taken.count(i));
  EXPECT_THROW(seeded_subset(1000, 951, 9, taken), OrchError);
  const auto whole = seeded_subset(16, 16, 1, {});
  EXPECT_EQ(std::set<std::uint64_t>(whole.begin(), whole.end()).size(), 16u);
}

TEST(VariationDistributions, UniformStaysInRangeWithTheRightMean) {
  const Moments m = moments_of(UniformDistribution{{10, 30}});
  EXPECT_GE(m.min, 10);
  EXPECT_LT(m.max, 30);
  EXPECT_NEAR(m.mean, 20, 0.2);
  EXPECT_NEAR(m.variance, 400.0 / 12, 400.0 / 12 * 0.05);
}

TEST(VariationDistributions, NormalHasItsMeanAndVariance) {
  const Moments m = moments_of(NormalDistribution{8, 6.25, std::nullopt});
  EXPECT_NEAR(m.mean, 8, 0.09);  // 5 standard errors: 5 * 2.5 / sqrt(20000)
  EXPECT_NEAR(m.variance, 6.25, 6.25 * 0.05);
}

TEST(VariationDistributions, NormalWithRangeIsTruncated) {
  const Moments m = moments_of(NormalDistribution{8, 6.25, ValueRange{4, 12}});
  EXPECT_GE(m.min, 4);
  EXPECT_LE(m.max, 12);
  EXPECT_NEAR(m.mean, 8, 0.09);  // symmetric truncation keeps the mean
  EXPECT_LT(m.variance, 6.25);
  // Far in a tail: after 64 misses the draw is clamped into the range, never outside it.
  const Moments tail = moments_of(NormalDistribution{0, 1, ValueRange{10, 11}});
  EXPECT_GE(tail.min, 10);
  EXPECT_LE(tail.max, 11);
}

TEST(VariationDistributions, LogNormalHasTheGivenMeanAndVarianceOfTheValue) {
  const Moments m = moments_of(LogNormalDistribution{10, 4, std::nullopt});
  EXPECT_GT(m.min, 0);
  EXPECT_NEAR(m.mean, 10, 0.07);
  EXPECT_NEAR(m.variance, 4, 4 * 0.06);
}

TEST(VariationDistributions, PoissonGivesWholeNumbersWithMeanAndVarianceLambda) {
  std::mt19937_64 engine(5);
  const PoissonDistribution d{3.5, std::nullopt};
  int zeros = 0;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double k = draw_stochastic(d, engine);
    ASSERT_EQ(k, std::floor(k));
    ASSERT_GE(k, 0);
    zeros += k == 0;
    sum += k;
    sum2 += k * k;
  }
  const double mean = sum / kDraws;
  EXPECT_NEAR(mean, 3.5, 0.07);
  EXPECT_NEAR(sum2 / kDraws - mean * mean, 3.5, 3.5 * 0.05);
  EXPECT_NEAR(static_cast<double>(zeros) / kDraws, std::exp(-3.5), 0.006);  // P(0) = e^-lambda
  const Moments ranged = moments_of(PoissonDistribution{3.5, ValueRange{2, 5}});
  EXPECT_GE(ranged.min, 2);
  EXPECT_LE(ranged.max, 5);
}

TEST(VariationDistributions, HistogramPicksBinsByWeightThenUniformWithin) {
  std::mt19937_64 engine(3);
  const HistogramDistribution d{{{1, {6, 12}}, {3, {12, 30}}}};
  int first = 0;
  double mean_first = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double x = draw_stochastic(d, engine);
    ASSERT_GE(x, 6);
    ASSERT_LT(x, 30);
    if (x < 12) {
      ++first;
      mean_first += x;
    }
  }
  EXPECT_NEAR(static_cast<double>(first) / kDraws, 0.25, 0.015);
  EXPECT_NEAR(mean_first / first, 9, 0.1);
}

TEST(VariationDistributions, ProbabilitySetFollowsItsWeights) {
  const Variation v = one_parameter("string", ProbabilityDistributionSet{{{"a", 1}, {"b", 2}, {"c", 1}}});
  std::map<std::string, int> counts;
  for (std::uint64_t seed = 1; seed <= kDraws; ++seed) ++counts[stochastic_values(v, seed).at(0).second];
  ASSERT_EQ(counts.size(), 3u);
  EXPECT_NEAR(counts["a"] / double(kDraws), 0.25, 0.02);
  EXPECT_NEAR(counts["b"] / double(kDraws), 0.50, 0.02);
  EXPECT_NEAR(counts["c"] / double(kDraws), 0.25, 0.02);
}

TEST(VariationDistributions, WholeNumberParametersGetWholeNumbers) {
  const Variation uniform = one_parameter("integer", UniformDistribution{{0.5, 3.2}});
  std::map<std::string, int> counts;
  for (std::uint64_t seed = 1; seed <= 3000; ++seed) ++counts[stochastic_values(uniform, seed).at(0).second];
  // 1, 2 and 3 alike (rounding would give the end points half the chance).
  EXPECT_EQ(counts.size(), 3u);
  for (const auto& [value, n] : counts) EXPECT_NEAR(n / 3000.0, 1.0 / 3, 0.04) << value;
  const Variation normal = one_parameter("unsignedInt", NormalDistribution{20, 9, ValueRange{0, 100}});
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    const std::string text = stochastic_values(normal, seed).at(0).second;
    EXPECT_EQ(text.find('.'), std::string::npos) << text;
  }
}

TEST(VariationDistributions, SameSeedSameValuesAndParametersDrawIndependently) {
  const auto logical = load_variation_logical(kNightly + "lead_brake_variation.xosc");
  Variation v = logical->variation;
  EXPECT_EQ(stochastic_values(v, 3), stochastic_values(v, 3));
  EXPECT_NE(stochastic_values(v, 3), stochastic_values(v, 4));
  const VariationValues before = stochastic_values(v, 3);
  // Dropping a parameter leaves the others' values alone (each has its own stream).
  v.distributions.erase(v.distributions.begin() + 1);
  const VariationValues after = stochastic_values(v, 3);
  EXPECT_EQ(after.at(0), before.at(0));
  EXPECT_EQ(after.at(1), before.at(2));
  // randomSeed changes every value.
  v.random_seed = 2;
  EXPECT_NE(stochastic_values(v, 3).at(0), before.at(0));
}

TEST(VariationSets, TheGridRunsEveryCombinationOnce) {
  const auto logical = load_variation_logical(kNightly + "lead_brake_grid_variation.xosc");
  const auto sets = all_variation_sets(*logical);
  ASSERT_EQ(sets.size(), 16u);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < sets.size(); ++i) {
    EXPECT_EQ(sets[i].seed, static_cast<long long>(i + 1));
    ids.insert(sets[i].uuid);
  }
  EXPECT_EQ(ids.size(), 16u);
  EXPECT_EQ(sets[0].sampled_values["param"]["Decel_mps2"], 4.0);
  EXPECT_EQ(sets[0].sumo_config.map, "motorway_3_lanes");
  EXPECT_EQ(variation_run_arguments(*logical, sets[15]),
            (std::vector<std::string>{"--param", "Decel_mps2=10.0", "--param", "LeadSpeed_kph=80.0", "--param",
                                      "Gap_m=8.0", "--param", "BrakeTime_s=6.0"}));
}

TEST(VariationSets, TheStochasticFileRunsNumberOfTestRunsDraws) {
  const auto logical = load_variation_logical(kNightly + "lead_brake_variation.xosc");
  const auto sets = all_variation_sets(*logical);
  ASSERT_EQ(sets.size(), 50u);
  for (const auto& s : sets) {
    const double speed = s.sampled_values["param"]["LeadSpeed_kph"].get<double>();
    EXPECT_GE(speed, 55);
    EXPECT_LT(speed, 78);
    const double decel = s.sampled_values["param"]["Decel_mps2"].get<double>();
    EXPECT_GE(decel, 4);
    EXPECT_LE(decel, 12);
  }
}

TEST(VariationSets, SampleDrawsASeededSubsetOfTheProduct) {
  const auto logical = load_variation_logical(kNightly + "lead_brake_grid_variation.xosc");
  SampleRequest request;
  request.count = 5;
  request.first_seed = 3;
  const SampleOutcome a = sample_variation_sets(*logical, request);
  const SampleOutcome b = sample_variation_sets(*logical, request);
  ASSERT_EQ(a.new_set_ids.size(), 5u);
  EXPECT_EQ(a.new_set_ids, b.new_set_ids);
  EXPECT_EQ(a.file.file, std::filesystem::path(kNightly + "lead_brake_grid_variation_parameters.json"));
  std::set<long long> seeds;
  for (const auto& s : a.file.sets) seeds.insert(*s.seed);
  EXPECT_EQ(seeds.size(), 5u);
  for (long long s : seeds) {
    EXPECT_GE(s, 1);
    EXPECT_LE(s, 16);
  }
  request.count = 17;
  EXPECT_THROW(sample_variation_sets(*logical, request), OrchError);
}

TEST(VariationSets, ASetThatBreaksTheScenarioIsRefused) {
  const auto logical = load_variation_logical(kNightly + "lead_brake_grid_variation.xosc");
  ParameterSet set = variation_set(*logical, 1);
  set.sampled_values["param"]["Decel_mps2"] = 0.0;  // lead_brake.xosc: Decel_mps2 > 0
  try {
    check_variation_set(*logical, set);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(e.diagnostics().format().find("violates its constraints"), std::string::npos) << e.diagnostics().format();
  }
  set = variation_set(*logical, 1);
  set.sampled_values["param"]["Gap_n"] = 3.0;
  try {
    check_variation_set(*logical, set);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(e.diagnostics().format().find("\"param.Gap_n\", which variation"), std::string::npos);
    EXPECT_NE(e.diagnostics().format().find("did you mean \"Gap_m\""), std::string::npos);
  }
}

}  // namespace
}  // namespace orch::batch
