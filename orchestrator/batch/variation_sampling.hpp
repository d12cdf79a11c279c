#pragma once
// Values of the runs of an OpenSCENARIO parameter variation (openscenario/variation.hpp),
// pure and identical on every platform (the transforms of batch/sampler.hpp):
//  - Deterministic: the full factorial product of its factors, in file order, the last
//    factor varying fastest; combination i (0-based) is the run with seed i + 1.
//  - Stochastic: the run with seed k draws every parameter from its own stream, seeded from
//    (k, randomSeed, parameter name), so the same seed always gives the same values.
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "openscenario/variation.hpp"

namespace orch::batch {

// (parameter name, value as the text `run --param NAME=VALUE` takes), in file order.
using VariationValues = std::vector<std::pair<std::string, std::string>>;

// Combinations of a deterministic variation; throws OrchError beyond 2^53.
std::uint64_t product_size(const openscenario::Variation& v);
// Combination `index` (0-based, < product_size).
VariationValues product_values(const openscenario::Variation& v, std::uint64_t index);
// The values of run `seed` of a stochastic variation.
VariationValues stochastic_values(const openscenario::Variation& v, std::uint64_t seed);

// One value of a stochastic distribution (before any rounding to the parameter's type).
// Normal, LogNormal and Poisson with a Range are truncated: drawn again outside it, the
// last of 64 draws clamped.
double draw_stochastic(const openscenario::StochasticKind& d, std::mt19937_64& engine);
// The parameter value text of a draw: whole-number types are rounded to the nearest.
std::string value_text(const openscenario::Parameter& p, double x);

// `count` distinct combinations of [0, size) not in `taken`, drawn with seed `seed`, in
// the order drawn. Throws OrchError when fewer than `count` are left.
std::vector<std::uint64_t> seeded_subset(std::uint64_t size, std::uint64_t count, std::uint64_t seed,
                                         const std::set<std::uint64_t>& taken);

// The value as the record keeps it: a number for numeric types, true/false for booleans,
// else the text.
nlohmann::json typed_value(const openscenario::Parameter& p, const std::string& text);

}  // namespace orch::batch
