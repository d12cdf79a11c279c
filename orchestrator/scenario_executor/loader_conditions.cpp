// Conditions: the groups of scenes' and stop conditions; each condition's own reader is in
// its row of scenario/condition_elements.cpp.
#include <fmt/format.h>

#include <algorithm>

#include "core/suggest.hpp"
#include "scenario_executor/elements.hpp"
#include "scenario_executor/loader_internal.hpp"

namespace orch::scenario_loading {

using namespace orch::scenario;

namespace {

std::vector<std::string> kinds_present(const nlohmann::json& object) {
  std::vector<std::string> present;
  for (const auto& kind : condition_kinds())
    if (object.contains(kind)) present.push_back(kind);
  return present;
}

ConditionGroup make_group(Logic logic, std::vector<ConditionItem> items, SourceLocation where) {
  ConditionGroup g;
  g.logic = logic;
  g.items = std::move(items);
  g.where = std::move(where);
  return g;
}

std::vector<ConditionItem> read_items(LoadContext& ctx, const nlohmann::json& array, const std::string& pointer);

// One entry of an "and" / "or" list: a condition such as {"speed": {...}} (with an optional
// "description" beside it), or a nested group {"and": [...]} / {"or": [...]}.
std::optional<ConditionItem> read_item(LoadContext& ctx, const nlohmann::json& item, const std::string& pointer) {
  if (!item.is_object()) {
    ctx.diags.error(ctx.doc.where(pointer),
                    fmt::format("expected a condition such as {{\"speed\": {{...}}}} or a group {{\"or\": [...]}}, "
                                "found {}",
                                json_type_name(item)));
    return std::nullopt;
  }
  const auto kinds = kinds_present(item);
  const bool is_group = item.contains("and") || item.contains("or");
  if (is_group && kinds.empty()) return ConditionItem{read_condition_group(ctx, item, pointer)};

  const int errors_before = ctx.diags.error_count();
  ObjectReader r(ctx.doc, item, pointer, ctx.diags, "condition");
  const auto outer_description = r.string("description", Need::Optional);
  r.allow(condition_kinds());
  if (is_group) {
    reject_key(r, item.contains("and") ? "and" : "or",
               "a list entry is either one condition or a group {\"and\"/\"or\": [...]}, not both; "
               "put the condition inside the group's list");
  }
  if (kinds.size() > 1) {
    r.error(kinds[1], fmt::format("one entry holds one condition, found \"{}\" and \"{}\"; give each its own "
                                  "entry of the list",
                                  kinds[0], kinds[1]));
  }
  if (kinds.empty()) {
    // An unknown key gets its "did you mean" from finish(); an empty object gets this.
    const bool only_description = item.size() == (outer_description ? 1u : 0u);
    if (only_description)
      r.error("", fmt::format("empty condition: expected one of {}", quoted_list(condition_kinds())));
    r.finish();
    return std::nullopt;
  }
  r.finish();

  const std::string& kind = kinds.front();
  ObjectReader body(ctx.doc, item[kind], r.child(kind), ctx.diags, kind + " condition");
  Condition condition;
  condition.where = body.where();
  const auto inner_description = body.string("description", Need::Optional);
  condition.description = inner_description.value_or(outer_description.value_or(""));
  const auto* element = scenario_elements::find_element(scenario_elements::condition_elements(), kind);
  auto parsed = body.is_object() ? element->read(ctx, body) : std::nullopt;
  body.finish();
  // A condition with an error of its own stays out of the model (see loader_internal.hpp).
  if (!parsed || ctx.diags.error_count() != errors_before) return std::nullopt;
  condition.kind = std::move(*parsed);
  return ConditionItem{std::move(condition)};
}

std::vector<ConditionItem> read_items(LoadContext& ctx, const nlohmann::json& array, const std::string& pointer) {
  std::vector<ConditionItem> items;
  for (std::size_t i = 0; i < array.size(); ++i)
    if (auto item = read_item(ctx, array[i], json_pointer_child(pointer, i))) items.push_back(std::move(*item));
  return items;
}

}  // namespace

ConditionGroup read_condition_group(LoadContext& ctx, const nlohmann::json& value, const std::string& pointer) {
  const SourceLocation where = ctx.doc.where(pointer);
  if (!value.is_object()) {
    ctx.diags.error(where, fmt::format("conditions must be an object {{\"and\": [...]}} or {{\"or\": [...]}}, "
                                       "found {}",
                                       json_type_name(value)));
    return make_group(Logic::And, {}, where);
  }
  ObjectReader r(ctx.doc, value, pointer, ctx.diags, "conditions");
  const auto* all = r.array("and", Need::Optional);
  const auto* any = r.array("or", Need::Optional);
  for (const auto& kind : kinds_present(value))
    reject_key(r, kind,
               fmt::format("a condition goes inside a list: {{\"and\": [{{\"{}\": {{...}}}}]}} or {{\"or\": [...]}}",
                           kind));
  r.finish();

  std::optional<ConditionGroup> all_group;
  std::optional<ConditionGroup> any_group;
  if (all) all_group = make_group(Logic::And, read_items(ctx, *all, r.child("and")), r.where("and"));
  if (any) any_group = make_group(Logic::Or, read_items(ctx, *any, r.child("or")), r.where("or"));
  if (all_group && any_group) {
    // Both keys in one object: both must hold.
    std::vector<ConditionItem> both;
    both.push_back(ConditionItem{std::move(*all_group)});
    both.push_back(ConditionItem{std::move(*any_group)});
    return make_group(Logic::And, std::move(both), where);
  }
  if (all_group) return make_group(Logic::And, std::move(all_group->items), where);
  if (any_group) return make_group(Logic::Or, std::move(any_group->items), where);
  return make_group(Logic::And, {}, where);  // {}: always true
}

}  // namespace orch::scenario_loading
