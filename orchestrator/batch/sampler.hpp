#pragma once
// Seeded sampling of a logical scenario's parameter space, identical on every platform.
//
// The standard library's distributions (uniform_real_distribution, normal_distribution)
// are allowed to differ between implementations; only the engines and std::seed_seq are
// specified to the bit. So every transform here is written out from std::mt19937_64's raw
// output: u = 53 random bits / 2^53, uniform = min + (max - min) * u, normal by Box-Muller.
//
// Each parameter draws from its own stream, seeded from (set seed, "group.name"), so adding
// or removing a parameter never changes the values the others get for the same seed.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "batch/logical_scenario.hpp"

namespace orch::batch {

// u in [0, 1) from the top 53 bits of one draw.
double unit_interval(std::mt19937_64& engine);
// A standard normal value from two draws (Box-Muller, cosine branch).
double standard_normal(std::mt19937_64& engine);
// The engine for one parameter of one parameter set.
std::mt19937_64 parameter_stream(std::uint64_t set_seed, const std::string& key);

nlohmann::json draw(const ParameterSpec& spec, std::mt19937_64& engine);
// {"group": {"name": value, ...}, ...} for every parameter of the space.
nlohmann::ordered_json sample_values(const LogicalScenario& logical, std::uint64_t set_seed);

}  // namespace orch::batch
