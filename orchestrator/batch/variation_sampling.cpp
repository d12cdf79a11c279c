#include "batch/variation_sampling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "batch/sampler.hpp"
#include "core/errors.hpp"
#include "openscenario/expression.hpp"
#include "openscenario/text_number.hpp"

namespace orch::batch {

namespace {

using namespace openscenario;

constexpr double kMaxCombinations = 9007199254740992.0;  // 2^53: indices stay exact doubles
constexpr int kTruncationTries = 64;

// Index of a weighted choice for u in [0, 1).
std::size_t weighted_index(const std::vector<double>& weights, double u) {
  double total = 0;
  for (double w : weights) total += w;
  double acc = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    acc += weights[i];
    if (u * total < acc) return i;
  }
  return weights.size() - 1;
}

double truncated(const std::optional<ValueRange>& range, const auto& one_draw) {
  double x = one_draw();
  if (!range) return x;
  for (int i = 1; i < kTruncationTries && (x < range->lower || x > range->upper); ++i) x = one_draw();
  return std::clamp(x, range->lower, range->upper);
}

struct StochasticDrawer {
  std::mt19937_64& engine;

  double operator()(const UniformDistribution& d) const {
    return d.range.lower + (d.range.upper - d.range.lower) * unit_interval(engine);
  }
  double operator()(const NormalDistribution& d) const {
    return truncated(d.range, [&] { return d.expected_value + std::sqrt(d.variance) * standard_normal(engine); });
  }
  double operator()(const LogNormalDistribution& d) const {
    // The log of the value is normal with mu, sigma^2 such that the value has the given
    // expected value m and variance v: sigma^2 = ln(1 + v / m^2), mu = ln m - sigma^2 / 2.
    const double sigma2 = std::log1p(d.variance / (d.expected_value * d.expected_value));
    const double mu = std::log(d.expected_value) - sigma2 / 2;
    return truncated(d.range, [&] { return std::exp(mu + std::sqrt(sigma2) * standard_normal(engine)); });
  }
  double operator()(const PoissonDistribution& d) const {
    // Inversion: the smallest k with P(X <= k) > u.
    return truncated(d.range, [&] {
      const double u = unit_interval(engine);
      double p = std::exp(-d.expected_value);
      double cumulative = p;
      long long k = 0;
      while (u >= cumulative && k < 100000) {
        ++k;
        p *= d.expected_value / static_cast<double>(k);
        cumulative += p;
        if (p == 0 && static_cast<double>(k) > d.expected_value) break;  // the tail underflowed
      }
      return static_cast<double>(k);
    });
  }
  double operator()(const HistogramDistribution& d) const {
    std::vector<double> weights;
    for (const auto& b : d.bins) weights.push_back(b.weight);
    const HistogramBin& bin = d.bins[weighted_index(weights, unit_interval(engine))];
    return bin.range.lower + (bin.range.upper - bin.range.lower) * unit_interval(engine);
  }
  double operator()(const ProbabilityDistributionSet&) const { return 0; }  // see stochastic_values
};

bool whole_number_type(const std::string& type) {
  return type == "integer" || type == "unsignedInt" || type == "unsignedShort";
}

}  // namespace

std::uint64_t product_size(const Variation& v) {
  double size = 1;
  for (const auto& f : v.factors) size *= static_cast<double>(f.options.size());
  if (size > kMaxCombinations)
    throw OrchError(fmt::format("{}: the product has {:.3g} combinations, more than 2^53", v.file, size));
  std::uint64_t n = 1;
  for (const auto& f : v.factors) n *= f.options.size();
  return n;
}

VariationValues product_values(const Variation& v, std::uint64_t index) {
  std::vector<std::size_t> choice(v.factors.size());
  for (std::size_t i = v.factors.size(); i-- > 0;) {
    const std::uint64_t n = v.factors[i].options.size();
    choice[i] = static_cast<std::size_t>(index % n);
    index /= n;
  }
  VariationValues out;
  for (std::size_t i = 0; i < v.factors.size(); ++i) {
    const auto& f = v.factors[i];
    for (std::size_t j = 0; j < f.parameters.size(); ++j) out.emplace_back(f.parameters[j], f.options[choice[i]][j]);
  }
  return out;
}

double draw_stochastic(const StochasticKind& d, std::mt19937_64& engine) { return std::visit(StochasticDrawer{engine}, d); }

std::string value_text(const Parameter& p, double x) {
  return format_number(whole_number_type(p.type) ? std::round(x) : x);
}

VariationValues stochastic_values(const Variation& v, std::uint64_t seed) {
  VariationValues out;
  for (const auto& s : v.distributions) {
    auto engine = parameter_stream(seed, fmt::format("{}/{}", format_number(v.random_seed), s.parameter));
    if (const auto* set = std::get_if<ProbabilityDistributionSet>(&s.distribution)) {
      std::vector<double> weights;
      for (const auto& e : set->elements) weights.push_back(e.weight);
      out.emplace_back(s.parameter, set->elements[weighted_index(weights, unit_interval(engine))].value);
      continue;
    }
    const Parameter* p = v.declaration(s.parameter);
    const auto* uniform = std::get_if<UniformDistribution>(&s.distribution);
    if (uniform && whole_number_type(p->type)) {
      // Every whole number of the range alike (rounding would halve the end points' chances).
      const double low = std::ceil(uniform->range.lower);
      const double count = std::floor(uniform->range.upper) - low + 1;
      if (count < 1)
        throw OrchError(fmt::format("{}:{}: the range of {} holds no whole number", v.file, s.where.line, s.parameter));
      out.emplace_back(s.parameter, format_number(low + std::min(std::floor(unit_interval(engine) * count), count - 1)));
      continue;
    }
    out.emplace_back(s.parameter, value_text(*p, draw_stochastic(s.distribution, engine)));
  }
  return out;
}

std::vector<std::uint64_t> seeded_subset(std::uint64_t size, std::uint64_t count, std::uint64_t seed,
                                         const std::set<std::uint64_t>& taken) {
  const std::uint64_t left = size - std::min<std::uint64_t>(size, taken.size());
  if (count > left)
    throw OrchError(fmt::format("--count {}: the product has {} combinations, {} of them not sampled yet", count, size, left));
  std::mt19937_64 engine(seed);
  std::set<std::uint64_t> chosen;
  std::vector<std::uint64_t> out;
  // Rejection of repeats: at most count <= left draws are kept, so this ends; when nearly
  // the whole product is asked for it takes longer, never wrongly.
  while (out.size() < count) {
    const double x = unit_interval(engine) * static_cast<double>(size);
    if (!(x < 0x1p64)) continue;  // a product of 2^64 rounds up to it: not an index
    const auto i = static_cast<std::uint64_t>(x);
    if (i >= size || taken.count(i) || !chosen.insert(i).second) continue;
    out.push_back(i);
  }
  return out;
}

nlohmann::json typed_value(const Parameter& p, const std::string& text) {
  if (whole_number_type(p.type))
    if (const auto n = parse_whole<long long>(text)) return *n;
  if (p.type == "double")
    if (const auto d = parse_whole<double>(text)) return *d;
  if (p.type == "boolean") return text == "true";
  return text;
}

}  // namespace orch::batch
