#pragma once
// The ScenarioExecutor format's scene elements, one table per element kind: every action
// (action_elements.cpp) and every condition (condition_elements.cpp) is one row holding its
// key in the file, its reader (used by the loader) and its checker (used by the validator).
// The engine's behaviour is one function per element type, dispatched by the model's
// variant (engine/engine_actions.cpp, engine/conditions.cpp); a type without one does not
// compile.
//
// Adding an action: its struct and variant alternative (model.hpp), its row with reader and
// checker (action_elements.cpp), its behaviour (Engine::act in engine_actions.cpp).
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "scenario_executor/loader_internal.hpp"
#include "scenario_executor/validator_internal.hpp"

namespace orch::scenario_elements {

template <typename Kind>
struct Element {
  std::string name;  // the key in the file: {"speed": {...}}
  // Reads the element's object; problems go to ctx.diags, nullopt when it cannot be built.
  std::optional<Kind> (*read)(scenario_loading::LoadContext& ctx, ObjectReader& body);
  // What the element refers to and its values, against the scenario, map and catalog. The
  // actor a kind names in `actor` (an ActorId) is checked for every kind before this runs.
  void (*check)(scenario_checks::CheckContext& ctx, const Kind& kind, const SourceLocation& where);
  bool (*holds)(const Kind& kind);  // the row of this alternative
};
using ActionElement = Element<scenario::ActionKind>;
using ConditionElement = Element<scenario::ConditionKind>;

const std::vector<ActionElement>& action_elements();
const std::vector<ConditionElement>& condition_elements();

// A row from the element's own reader (returning std::optional<T>) and checker (taking
// const T&), T its model struct.
template <typename Kind, auto Read, auto Check>
Element<Kind> row(std::string name) {
  using T = typename std::invoke_result_t<decltype(Read), scenario_loading::LoadContext&, ObjectReader&>::value_type;
  static_assert(std::is_invocable_v<decltype(Check), scenario_checks::CheckContext&, const T&, const SourceLocation&>);
  return {std::move(name),
          [](scenario_loading::LoadContext& ctx, ObjectReader& body) -> std::optional<Kind> {
            if (auto value = Read(ctx, body)) return Kind{std::move(*value)};
            return std::nullopt;
          },
          [](scenario_checks::CheckContext& ctx, const Kind& kind, const SourceLocation& where) {
            Check(ctx, std::get<T>(kind), where);
          },
          [](const Kind& kind) { return std::holds_alternative<T>(kind); }};
}

template <typename Kind>
std::vector<std::string> element_names(const std::vector<Element<Kind>>& table) {
  std::vector<std::string> out;
  for (const auto& e : table) out.push_back(e.name);
  return out;
}

template <typename Kind>
const Element<Kind>* find_element(const std::vector<Element<Kind>>& table, std::string_view name) {
  for (const auto& e : table)
    if (e.name == name) return &e;
  return nullptr;
}

// The row of a model value; null for a value no row makes (the empty action `{}`).
template <typename Kind>
const Element<Kind>* element_of(const std::vector<Element<Kind>>& table, const Kind& kind) {
  for (const auto& e : table)
    if (e.holds(kind)) return &e;
  return nullptr;
}

}  // namespace orch::scenario_elements
