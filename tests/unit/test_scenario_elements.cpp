// The element tables (scenario_executor/elements.hpp): one row per model type, one key per row, and
// the loader reads exactly the keys the tables name.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "scenario_executor/elements.hpp"

using namespace orch;
using namespace orch::scenario;
using namespace orch::scenario_elements;

namespace {

// How many rows claim each alternative of the variant (default-constructed).
template <typename Kind, std::size_t... I>
std::vector<int> rows_per_alternative(const std::vector<Element<Kind>>& table, std::index_sequence<I...>) {
  std::vector<int> counts;
  (
      [&] {
        const Kind value{std::in_place_index<I>};
        int n = 0;
        for (const auto& e : table) n += e.holds(value) ? 1 : 0;
        counts.push_back(n);
      }(),
      ...);
  return counts;
}

template <typename Kind>
std::vector<int> rows_per_alternative(const std::vector<Element<Kind>>& table) {
  return rows_per_alternative(table, std::make_index_sequence<std::variant_size_v<Kind>>{});
}

}  // namespace

TEST(ScenarioElements, EveryActionTypeHasOneRowButTheEmptyAction) {
  const auto counts = rows_per_alternative(action_elements());
  const std::size_t empty_index = ActionKind{EmptyAction{}}.index();
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const bool empty = i == empty_index;
    EXPECT_EQ(counts[i], empty ? 0 : 1) << "ActionKind alternative " << i;
  }
}

TEST(ScenarioElements, EveryConditionTypeHasOneRow) {
  for (const int n : rows_per_alternative(condition_elements())) EXPECT_EQ(n, 1);
}

TEST(ScenarioElements, NamesAreUniqueAndFoundByName) {
  for (const auto& names : {element_names(action_elements()), element_names(condition_elements())}) {
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
    for (const auto& n : names) EXPECT_FALSE(n.empty());
  }
  EXPECT_EQ(find_element(action_elements(), "lane_change")->name, "lane_change");
  EXPECT_EQ(find_element(action_elements(), "lane_chnage"), nullptr);
  const ConditionKind speed = SpeedCondition{};
  EXPECT_EQ(element_of(condition_elements(), speed)->name, "speed");
}
