#pragma once
// OpenSCENARIO parameter variation files (`*_variation.xosc`, root child
// ParameterValueDistribution): a referenced scenario file and the distributions of some of
// its parameters. Deterministic distributions are read into the factors of a full factorial
// product (every option of every factor, combined); Stochastic ones into per-parameter
// distributions drawn `numberOfTestRuns` times. Read into plain values, checked against the
// referenced scenario's ParameterDeclarations; errors name file, line and element path.
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "openscenario/model.hpp"

namespace orch::openscenario {

struct ValueRange {
  double lower = 0;
  double upper = 0;
};

// One factor of the deterministic product: a DeterministicSingleParameterDistribution (one
// parameter, the values of its DistributionSet or DistributionRange) or a
// DeterministicMultiParameterDistribution (several parameters, one ParameterValueSet each).
struct DeterministicFactor {
  std::vector<std::string> parameters;
  std::vector<std::vector<std::string>> options;  // options[i][j]: value of parameters[j]
  // (option, parameter) pairs a ParameterValueSet does not assign: the scenario's default.
  std::vector<std::pair<std::size_t, std::size_t>> scenario_defaults;
  Place where;
};

struct UniformDistribution {
  ValueRange range;
};
struct NormalDistribution {  // of the value itself; Range truncates (drawn again)
  double expected_value = 0;
  double variance = 0;
  std::optional<ValueRange> range;
};
struct LogNormalDistribution {  // expectedValue and variance of the value, not of its log
  double expected_value = 0;
  double variance = 0;
  std::optional<ValueRange> range;
};
struct PoissonDistribution {
  double expected_value = 0;
  std::optional<ValueRange> range;
};
struct HistogramBin {
  double weight = 0;
  ValueRange range;
};
struct HistogramDistribution {
  std::vector<HistogramBin> bins;
};
struct WeightedValue {
  std::string value;
  double weight = 0;
};
struct ProbabilityDistributionSet {
  std::vector<WeightedValue> elements;
};
using StochasticKind = std::variant<UniformDistribution, NormalDistribution, LogNormalDistribution,
                                    PoissonDistribution, HistogramDistribution, ProbabilityDistributionSet>;

struct StochasticParameter {
  std::string parameter;
  StochasticKind distribution;
  Place where;
};

struct Variation {
  std::string file;
  std::string scenario_file;  // absolute, resolved against the variation file's folder
  int rev_minor = 0;
  bool stochastic = false;
  std::vector<DeterministicFactor> factors;        // Deterministic
  std::vector<StochasticParameter> distributions;  // Stochastic
  long long number_of_test_runs = 0;               // Stochastic
  double random_seed = 0;                          // Stochastic (0 when not given)
  // The referenced scenario's declarations (name, type, default value) and road.
  std::vector<Parameter> declared;
  std::string road_file;

  // Every varied parameter, in file order.
  [[nodiscard]] std::vector<std::string> parameter_names() const;
  [[nodiscard]] const Parameter* declaration(const std::string& name) const;
};

// True when `path` is an OpenSCENARIO file whose root holds a ParameterValueDistribution.
bool is_variation_file(const std::string& path);

// Reads the variation and loads its scenario (defaults only) for the declarations. Throws
// ScenarioError: unknown or misspelt elements and attributes (did you mean), a missing
// scenario file, a parameter the scenario does not declare (did you mean), a value that does
// not fit the parameter's type, a parameter varied twice, empty or inverted ranges, weights
// that are not positive, a distribution that cannot give values of the parameter's type.
Variation load_variation(const std::string& path);

}  // namespace orch::openscenario
