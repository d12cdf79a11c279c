#include "batch/sampler.hpp"

#include <cmath>
#include <numbers>

#include "core/checked_numeric.hpp"
#include "core/stable_hash.hpp"

namespace orch::batch {

namespace {

nlohmann::json as_type(ValueType type, double x) {
  if (type == ValueType::Int) return clamped_round<long long>(x, -(1LL << 53), 1LL << 53);
  return x;
}

struct Drawer {
  const ParameterSpec& spec;
  std::mt19937_64& engine;

  nlohmann::json operator()(const Constant& c) const { return c.value; }

  nlohmann::json operator()(const Uniform& u) const {
    const double x = unit_interval(engine);
    if (spec.type == ValueType::Int) {
      // Every whole number of [min, max] equally likely.
      const double count = u.max - u.min + 1.0;
      return clamped_floor<long long>(u.min + std::min(std::floor(x * count), count - 1.0), -(1LL << 53), 1LL << 53);
    }
    return u.min + (u.max - u.min) * x;
  }

  nlohmann::json operator()(const Normal& n) const {
    const auto inside = [&](double v) { return (!n.min || v >= *n.min) && (!n.max || v <= *n.max); };
    // Truncation by rejection; after 64 misses (bounds far in a tail) the last draw is
    // clamped, so sampling always ends and stays within the declared bounds.
    double v = 0;
    for (int attempt = 0; attempt < 64; ++attempt) {
      v = n.mean + n.std * standard_normal(engine);
      if (spec.type == ValueType::Int) v = std::round(v);
      if (inside(v)) return as_type(spec.type, v);
    }
    if (n.min) v = std::max(v, *n.min);
    if (n.max) v = std::min(v, *n.max);
    return as_type(spec.type, v);
  }

  nlohmann::json operator()(const Choice& c) const {
    const auto count = static_cast<double>(c.choices.size());
    const auto index = static_cast<std::size_t>(std::min(std::floor(unit_interval(engine) * count), count - 1.0));
    return c.choices[index];
  }
};

}  // namespace

double standard_normal(std::mt19937_64& engine) {
  // Box-Muller, cosine branch only: one normal per two uniforms keeps each draw
  // independent of what was drawn before it. 1 - u lies in (0, 1], so log never sees 0.
  const double u1 = 1.0 - unit_interval(engine);
  const double u2 = unit_interval(engine);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double unit_interval(std::mt19937_64& engine) {
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

std::mt19937_64 parameter_stream(std::uint64_t set_seed, const std::string& key) {
  const std::uint64_t h = stable_hash(key);
  std::seed_seq seq{static_cast<std::uint32_t>(set_seed), static_cast<std::uint32_t>(set_seed >> 32),
                    static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(h >> 32)};
  return std::mt19937_64(seq);
}

nlohmann::json draw(const ParameterSpec& spec, std::mt19937_64& engine) {
  return std::visit(Drawer{spec, engine}, spec.distribution);
}

nlohmann::ordered_json sample_values(const LogicalScenario& logical, std::uint64_t set_seed) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const auto& p : logical.parameters) {
    auto engine = parameter_stream(set_seed, p.key());
    out[p.group][p.name] = nlohmann::ordered_json(draw(p, engine));
  }
  return out;
}

}  // namespace orch::batch
