#pragma once
// The parameter space `orchestrator search` explores: every parameter of a logical scenario
// (or of an OpenSCENARIO variation) that takes numbers over a range, mapped to the unit cube;
// constants and parameters fixed with `--set KEY=VALUE` are not searched. A range can be
// narrowed with `--set KEY=LOW..HIGH`. A parameter that takes strings or booleans cannot be
// searched: it must be fixed.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch/logical_scenario.hpp"
#include "batch/search_proposal.hpp"
#include "batch/variation_batch.hpp"

namespace orch::batch {

struct SearchDimension {
  std::string key;  // "lead.decel" (JSON logical) or "Decel_mps2" (variation)
  std::string unit;
  double lower = 0;
  double upper = 0;
  bool integer = false;
  std::vector<double> choices;  // a choice of numbers: the value snaps to the nearest
};

struct SearchSpace {
  std::vector<SearchDimension> dims;
  // Values of the parameters not searched, by key (constants, --set).
  std::vector<std::pair<std::string, nlohmann::json>> fixed;

  [[nodiscard]] std::vector<std::string> keys() const;
  // Unit-cube point -> parameter values (whole numbers rounded, choices snapped).
  [[nodiscard]] std::vector<double> values(const Point& unit) const;
  // The unit-cube point of what `values` gives: proposals are snapped so runs and the model agree.
  [[nodiscard]] Point snap(const Point& unit) const;
  [[nodiscard]] Point to_unit(const std::vector<double>& values) const;
};

// Parses `--set` words: "KEY=VALUE" (a number, true/false or text) or "KEY=LOW..HIGH".
struct SpaceOverride {
  std::string key;
  nlohmann::json value;  // null for a range
  double low = 0, high = 0;
  [[nodiscard]] bool is_range() const { return value.is_null(); }
};
// Throws OrchError naming the word and what was expected.
SpaceOverride parse_space_override(const std::string& word);

// Throws OrchError: an override of an unknown parameter (did you mean), a range outside the
// parameter's, a parameter of strings or booleans left free, no parameter left to search.
SearchSpace logical_search_space(const LogicalScenario& logical, const std::vector<SpaceOverride>& overrides);
SearchSpace variation_search_space(const VariationLogical& v, const std::vector<SpaceOverride>& overrides);

// The set's `sampled_values` for one point: {"group": {"name": value}} of every parameter;
// `flat_keys` (a variation) puts every key under the group "param".
nlohmann::json sampled_values_of(const SearchSpace& space, const std::vector<double>& values, bool flat_keys);

}  // namespace orch::batch
