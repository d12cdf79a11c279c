// Seeded sampling: exact values, computed independently (a Python transcription of the
// C++ standard's std::seed_seq and std::mt19937_64 with the same transforms), so any
// platform or library that drifts from them fails here.
#include <gtest/gtest.h>

#include "batch/logical_scenario.hpp"
#include "batch/sampler.hpp"
#include "json/json_document.hpp"

using namespace orch;
using namespace orch::batch;

namespace {

LogicalScenario four_distributions() {
  const std::string text = R"({
    "uuid": "L1", "template": "../../scenarios/highway_cut_in.json",
    "parameter_space": {
      "ego": {
        "speed": {"type": "float", "unit": "km/h", "distribution": "uniform", "min": 20, "max": 40},
        "count": {"type": "int", "distribution": "uniform", "min": 1, "max": 6}
      },
      "env": {
        "noise": {"type": "float", "distribution": "normal", "mean": 50, "std": 10},
        "weather": {"type": "string", "distribution": "choice", "choices": ["A", "B", "C"]},
        "offset": {"type": "float", "unit": "m", "distribution": "constant", "value": -6.0}
      }
    }})";
  return read_logical_scenario(JsonDocument::parse(text, std::string(ORCH_SOURCE_DIR) + "/tests/unit/logical_L1.json"));
}

}  // namespace

TEST(BatchSampler, EngineIsTheStandardMt19937_64) {
  std::mt19937_64 engine;  // the standard fixes its 10000th output
  for (int i = 0; i < 9999; ++i) engine();
  EXPECT_EQ(engine(), 9981545732273789042ull);
}

TEST(BatchSampler, UnitIntervalUsesTheTop53Bits) {
  std::mt19937_64 engine;
  std::mt19937_64 copy = engine;
  const double u = unit_interval(engine);
  EXPECT_EQ(u, static_cast<double>(copy() >> 11) / 9007199254740992.0);
  EXPECT_GE(u, 0.0);
  EXPECT_LT(u, 1.0);
}

TEST(BatchSampler, Seed42GivesExactlyTheReferenceValues) {
  const auto values = sample_values(four_distributions(), 42);
  EXPECT_EQ(values["ego"]["speed"].get<double>(), 20.49371948861537);
  EXPECT_EQ(values["ego"]["count"].get<long long>(), 4);
  EXPECT_TRUE(values["ego"]["count"].is_number_integer());
  EXPECT_EQ(values["env"]["noise"].get<double>(), 30.71935031721774);
  EXPECT_EQ(values["env"]["weather"], "A");
  EXPECT_EQ(values["env"]["offset"].get<double>(), -6.0);
}

TEST(BatchSampler, Seed7GivesExactlyTheReferenceValues) {
  const auto values = sample_values(four_distributions(), 7);
  EXPECT_EQ(values["ego"]["speed"].get<double>(), 23.15220874145195);
  EXPECT_EQ(values["ego"]["count"].get<long long>(), 3);
  EXPECT_EQ(values["env"]["noise"].get<double>(), 53.57277315840824);
  EXPECT_EQ(values["env"]["weather"], "C");
}

TEST(BatchSampler, SameSeedSameValuesAndAddingAParameterChangesNoOther) {
  const LogicalScenario base = four_distributions();
  EXPECT_EQ(sample_values(base, 99).dump(), sample_values(base, 99).dump());
  EXPECT_NE(sample_values(base, 99).dump(), sample_values(base, 100).dump());
  LogicalScenario more = base;
  ParameterSpec extra;
  extra.group = "aaa";
  extra.name = "first";
  extra.distribution = Uniform{0, 1};
  more.parameters.insert(more.parameters.begin(), extra);
  const auto a = sample_values(base, 99);
  const auto b = sample_values(more, 99);
  EXPECT_EQ(a["ego"].dump(), b["ego"].dump());
  EXPECT_EQ(a["env"].dump(), b["env"].dump());
}

TEST(BatchSampler, DrawsStayInsideTheirDistributions) {
  ParameterSpec u{"g", "u", ValueType::Float, "", "", Uniform{-2.5, 7.5}, {}};
  ParameterSpec i{"g", "i", ValueType::Int, "", "", Uniform{3, 5}, {}};
  ParameterSpec n{"g", "n", ValueType::Float, "", "", Normal{0, 10, -1.0, 2.0}, {}};
  ParameterSpec c{"g", "c", ValueType::Bool, "", "", Choice{{true, false}}, {}};
  std::set<long long> ints;
  std::set<bool> bools;
  for (std::uint64_t seed = 0; seed < 2000; ++seed) {
    auto e1 = parameter_stream(seed, "g.u");
    const double x = draw(u, e1).get<double>();
    EXPECT_GE(x, -2.5);
    EXPECT_LT(x, 7.5);
    auto e2 = parameter_stream(seed, "g.i");
    ints.insert(draw(i, e2).get<long long>());
    auto e3 = parameter_stream(seed, "g.n");
    const double y = draw(n, e3).get<double>();  // truncated to [-1, 2]
    EXPECT_GE(y, -1.0);
    EXPECT_LE(y, 2.0);
    auto e4 = parameter_stream(seed, "g.c");
    bools.insert(draw(c, e4).get<bool>());
  }
  EXPECT_EQ(ints, (std::set<long long>{3, 4, 5}));  // both ends reachable, nothing beyond
  EXPECT_EQ(bools.size(), 2u);
}

TEST(BatchSampler, NormalHasItsMeanAndSpread) {
  ParameterSpec n{"g", "n", ValueType::Float, "", "", Normal{50, 10, std::nullopt, std::nullopt}, {}};
  double sum = 0, sum2 = 0;
  const int count = 20000;
  for (int s = 0; s < count; ++s) {
    auto e = parameter_stream(static_cast<std::uint64_t>(s), "g.n");
    const double x = draw(n, e).get<double>();
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / count;
  EXPECT_NEAR(mean, 50.0, 0.3);
  EXPECT_NEAR(std::sqrt(sum2 / count - mean * mean), 10.0, 0.3);
}
