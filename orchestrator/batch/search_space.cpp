#include "batch/search_space.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/errors.hpp"
#include "core/suggest.hpp"

namespace orch::batch {

namespace {

std::optional<double> number_of(const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

const SpaceOverride* override_of(const std::vector<SpaceOverride>& overrides, const std::string& key) {
  for (const auto& o : overrides)
    if (o.key == key) return &o;
  return nullptr;
}

void check_override_keys(const std::vector<SpaceOverride>& overrides, const std::vector<std::string>& keys,
                         const std::string& file) {
  std::set<std::string> seen;
  for (const auto& o : overrides) {
    if (std::find(keys.begin(), keys.end(), o.key) == keys.end())
      throw OrchError(fmt::format("--set {}: {} has no parameter \"{}\"{} (its parameters: {})", o.key, file, o.key,
                                  did_you_mean(o.key, keys), fmt::join(keys, ", ")));
    if (!seen.insert(o.key).second) throw OrchError(fmt::format("--set {}: given twice", o.key));
  }
}

// Adds a numeric range as a dimension, or as a fixed value when --set fixes it or narrows it
// to one point.
void add_range(SearchSpace& space, SearchDimension dim, const std::vector<SpaceOverride>& overrides) {
  if (const SpaceOverride* o = override_of(overrides, dim.key)) {
    if (!o->is_range()) {
      space.fixed.emplace_back(dim.key, o->value);
      return;
    }
    if (o->low < dim.lower - 1e-9 || o->high > dim.upper + 1e-9)
      throw OrchError(fmt::format("--set {}={:g}..{:g}: outside the parameter's range {:g}..{:g}", dim.key, o->low,
                                  o->high, dim.lower, dim.upper));
    dim.lower = o->low;
    dim.upper = o->high;
    if (!dim.choices.empty()) {
      std::erase_if(dim.choices, [&](double c) { return c < o->low - 1e-9 || c > o->high + 1e-9; });
      if (dim.choices.empty())
        throw OrchError(fmt::format("--set {}={:g}..{:g}: none of its choices is in that range", dim.key, o->low, o->high));
    }
  }
  if (dim.upper - dim.lower < 1e-12) {
    space.fixed.emplace_back(dim.key, dim.integer ? nlohmann::json(std::llround(dim.lower)) : nlohmann::json(dim.lower));
    return;
  }
  space.dims.push_back(std::move(dim));
}

[[noreturn]] void not_searchable(const std::string& key, const std::string& what, const std::string& file) {
  throw OrchError(fmt::format("{}: parameter \"{}\" {}: it cannot be searched; fix it with --set {}=VALUE", file, key,
                              what, key));
}

void finish(const SearchSpace& space, const std::string& file) {
  if (space.dims.empty())
    throw OrchError(fmt::format("{}: no parameter is left to search (every one is constant or fixed with --set)", file));
}

}  // namespace

std::vector<std::string> SearchSpace::keys() const {
  std::vector<std::string> out;
  for (const auto& d : dims) out.push_back(d.key);
  return out;
}

std::vector<double> SearchSpace::values(const Point& unit) const {
  std::vector<double> out;
  for (std::size_t j = 0; j < dims.size(); ++j) {
    const SearchDimension& d = dims[j];
    double v = d.lower + std::clamp(unit[j], 0.0, 1.0) * (d.upper - d.lower);
    if (!d.choices.empty()) {
      v = *std::min_element(d.choices.begin(), d.choices.end(),
                            [&](double a, double b) { return std::abs(a - v) < std::abs(b - v); });
    } else if (d.integer) {
      v = std::clamp(std::round(v), std::ceil(d.lower), std::floor(d.upper));
    }
    out.push_back(v);
  }
  return out;
}

Point SearchSpace::to_unit(const std::vector<double>& values) const {
  Point out;
  for (std::size_t j = 0; j < dims.size(); ++j) out.push_back((values[j] - dims[j].lower) / (dims[j].upper - dims[j].lower));
  return out;
}

Point SearchSpace::snap(const Point& unit) const { return to_unit(values(unit)); }

SpaceOverride parse_space_override(const std::string& word) {
  const auto eq = word.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == word.size())
    throw OrchError(fmt::format("--set \"{}\": expected KEY=VALUE or KEY=LOW..HIGH", word));
  SpaceOverride o;
  o.key = word.substr(0, eq);
  const std::string text = word.substr(eq + 1);
  if (const auto dots = text.find(".."); dots != std::string::npos) {
    const auto low = number_of(text.substr(0, dots));
    const auto high = number_of(text.substr(dots + 2));
    if (!low || !high || *low > *high)
      throw OrchError(fmt::format("--set \"{}\": expected a range LOW..HIGH of numbers with LOW <= HIGH", word));
    o.low = *low;
    o.high = *high;
    return o;
  }
  if (const auto n = number_of(text)) o.value = *n;
  else if (text == "true" || text == "false") o.value = text == "true";
  else o.value = text;
  return o;
}

SearchSpace logical_search_space(const LogicalScenario& logical, const std::vector<SpaceOverride>& overrides) {
  const std::string file = logical.file.string();
  check_override_keys(overrides, logical.keys(), file);
  SearchSpace space;
  for (const auto& p : logical.parameters) {
    const std::string key = p.key();
    const bool numeric = p.type == ValueType::Float || p.type == ValueType::Int;
    SearchDimension dim{key, p.unit, 0, 0, p.type == ValueType::Int, {}};
    const SpaceOverride* o = override_of(overrides, key);
    if (o && !o->is_range()) {
      space.fixed.emplace_back(key, o->value);
      continue;
    }
    if (const auto* c = std::get_if<Constant>(&p.distribution)) {
      if (o) throw OrchError(fmt::format("--set {}: the parameter is a constant; give one value, not a range", key));
      space.fixed.emplace_back(key, c->value);
      continue;
    }
    if (!numeric) not_searchable(key, fmt::format("takes {} values", type_name(p.type)), file);
    if (const auto* u = std::get_if<Uniform>(&p.distribution)) {
      dim.lower = u->min;
      dim.upper = u->max;
    } else if (const auto* n = std::get_if<Normal>(&p.distribution)) {
      dim.lower = n->min.value_or(n->mean - 3 * n->std);
      dim.upper = n->max.value_or(n->mean + 3 * n->std);
    } else if (const auto* ch = std::get_if<Choice>(&p.distribution)) {
      for (const auto& v : ch->choices) {
        if (!v.is_number()) not_searchable(key, "is a choice of values that are not all numbers", file);
        dim.choices.push_back(v.get<double>());
      }
      std::sort(dim.choices.begin(), dim.choices.end());
      dim.lower = dim.choices.front();
      dim.upper = dim.choices.back();
    }
    add_range(space, dim, overrides);
  }
  finish(space, file);
  return space;
}

SearchSpace variation_search_space(const VariationLogical& v, const std::vector<SpaceOverride>& overrides) {
  const openscenario::Variation& var = v.variation;
  const std::string file = v.logical.file.string();
  const std::vector<std::string> names = var.parameter_names();
  check_override_keys(overrides, names, file);
  SearchSpace space;
  std::set<std::string> done;
  const auto is_integer = [&](const std::string& name) {
    const auto* d = var.declaration(name);
    return d && (d->type == "integer" || d->type == "unsignedInt" || d->type == "unsignedShort");
  };
  const auto is_numeric = [&](const std::string& name) {
    const auto* d = var.declaration(name);
    return d && (d->type == "double" || is_integer(name));
  };
  const auto fixed_by_set = [&](const std::string& name) {
    const SpaceOverride* o = override_of(overrides, name);
    if (o && !o->is_range()) {
      space.fixed.emplace_back(name, o->value);
      return true;
    }
    return false;
  };
  for (const auto& factor : var.factors) {
    if (factor.parameters.size() > 1) {
      for (const auto& name : factor.parameters)
        if (!fixed_by_set(name))
          not_searchable(name, "is varied together with others (a ValueSetDistribution)", file);
      continue;
    }
    const std::string& name = factor.parameters.front();
    if (fixed_by_set(name)) continue;
    if (!is_numeric(name)) not_searchable(name, "is not a number", file);
    SearchDimension dim{name, "", 0, 0, is_integer(name), {}};
    std::vector<double> options;
    for (const auto& option : factor.options)
      if (const auto n = number_of(option.front())) options.push_back(*n);
    if (options.empty()) not_searchable(name, "has no numeric values", file);
    // A DistributionRange or DistributionSet of numbers: the search takes the whole range.
    dim.lower = *std::min_element(options.begin(), options.end());
    dim.upper = *std::max_element(options.begin(), options.end());
    add_range(space, dim, overrides);
  }
  for (const auto& sp : var.distributions) {
    const std::string& name = sp.parameter;
    if (fixed_by_set(name)) continue;
    if (!is_numeric(name)) not_searchable(name, "is not a number", file);
    SearchDimension dim{name, "", 0, 0, is_integer(name), {}};
    const auto range_or = [&](const std::optional<openscenario::ValueRange>& r, double mean, double sd) {
      dim.lower = r ? r->lower : mean - 3 * sd;
      dim.upper = r ? r->upper : mean + 3 * sd;
    };
    std::visit(
        [&](const auto& d) {
          using T = std::decay_t<decltype(d)>;
          if constexpr (std::is_same_v<T, openscenario::UniformDistribution>) {
            dim.lower = d.range.lower;
            dim.upper = d.range.upper;
          } else if constexpr (std::is_same_v<T, openscenario::NormalDistribution> ||
                               std::is_same_v<T, openscenario::LogNormalDistribution>) {
            range_or(d.range, d.expected_value, std::sqrt(d.variance));
            if constexpr (std::is_same_v<T, openscenario::LogNormalDistribution>) dim.lower = std::max(dim.lower, 0.0);
          } else if constexpr (std::is_same_v<T, openscenario::PoissonDistribution>) {
            range_or(d.range, d.expected_value, std::sqrt(d.expected_value));
            dim.lower = std::max(dim.lower, 0.0);
            dim.integer = true;
          } else if constexpr (std::is_same_v<T, openscenario::HistogramDistribution>) {
            dim.lower = d.bins.front().range.lower;
            dim.upper = d.bins.back().range.upper;
            for (const auto& b : d.bins) {
              dim.lower = std::min(dim.lower, b.range.lower);
              dim.upper = std::max(dim.upper, b.range.upper);
            }
          } else {
            for (const auto& e : d.elements) {
              const auto n = number_of(e.value);
              if (!n) not_searchable(name, "is a set of values that are not all numbers", file);
              dim.choices.push_back(*n);
            }
            std::sort(dim.choices.begin(), dim.choices.end());
            dim.lower = dim.choices.front();
            dim.upper = dim.choices.back();
          }
        },
        sp.distribution);
    add_range(space, dim, overrides);
  }
  finish(space, file);
  return space;
}

nlohmann::json sampled_values_of(const SearchSpace& space, const std::vector<double>& values, bool flat_keys) {
  nlohmann::json out = nlohmann::json::object();
  const auto put = [&](const std::string& key, const nlohmann::json& value) {
    if (flat_keys) {
      out[kVariationGroup][key] = value;
      return;
    }
    const auto dot = key.find('.');
    out[key.substr(0, dot)][key.substr(dot + 1)] = value;
  };
  for (const auto& [key, value] : space.fixed) put(key, value);
  for (std::size_t j = 0; j < space.dims.size(); ++j)
    put(space.dims[j].key, space.dims[j].integer ? nlohmann::json(std::llround(values[j])) : nlohmann::json(values[j]));
  return out;
}

}  // namespace orch::batch
