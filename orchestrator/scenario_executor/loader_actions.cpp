// Actions of scenes: each entry of "actions" holds exactly one action key (plus an optional
// "description"); `{}` is accepted as an action that does nothing. Each action's own reader
// is in its row of scenario/action_elements.cpp.
#include <fmt/format.h>

#include "scenario_executor/elements.hpp"
#include "scenario_executor/loader_internal.hpp"

namespace orch::scenario_loading {

using namespace orch::scenario;

namespace {

std::optional<Accel> read_accel(LoadContext& ctx, ObjectReader& parent) {
  const auto* value = parent.object("accel", Need::Optional);
  // Absent accel: the speed is set at once ("gods_hand"), as in the reference implementation.
  if (!parent.has("accel")) return Accel{AccelType::GodsHand, 0};
  if (!value) return std::nullopt;
  ObjectReader r(ctx.doc, *value, parent.child("accel"), ctx.diags, "accel");
  // The document spells it "gods_hand", the reference implementation "god_hands".
  const auto type = r.choice("type", {"specify", "gods_hand", "god_hands"}, Need::Required);
  const bool specify = type && *type == "specify";
  const auto magnitude = r.number("value", specify ? Need::Required : Need::Optional, Quantity::Acceleration);
  r.finish();
  if (!type || (specify && !magnitude)) return std::nullopt;
  return Accel{specify ? AccelType::Specify : AccelType::GodsHand, magnitude.value_or(0.0)};
}

std::optional<Action> read_action(LoadContext& ctx, const nlohmann::json& item, const std::string& pointer) {
  if (!item.is_object()) {
    ctx.diags.error(ctx.doc.where(pointer),
                    fmt::format("expected an action such as {{\"speed\": {{...}}}}, found {}", json_type_name(item)));
    return std::nullopt;
  }
  const int errors_before = ctx.diags.error_count();
  ObjectReader r(ctx.doc, item, pointer, ctx.diags, "action");
  const auto outer_description = r.string("description", Need::Optional);
  r.allow(action_kinds());
  std::vector<std::string> kinds;
  for (const auto& kind : action_kinds())
    if (item.contains(kind)) kinds.push_back(kind);
  if (kinds.size() > 1)
    r.error(kinds[1], fmt::format("one entry of \"actions\" holds exactly one action, found \"{}\" and \"{}\"; "
                                  "give each its own entry",
                                  kinds[0], kinds[1]));
  if (kinds.empty()) {
    r.finish();  // unknown keys, with "did you mean"
    if (ctx.diags.error_count() != errors_before) return std::nullopt;
    // `{}` (real files have it): does nothing, but it is probably an unfinished edit.
    r.warning("", "empty action: it does nothing");
    return Action{EmptyAction{}, outer_description.value_or(""), r.where()};
  }
  r.finish();

  const std::string& kind = kinds.front();
  ObjectReader body(ctx.doc, item[kind], r.child(kind), ctx.diags, kind + " action");
  const auto inner_description = body.string("description", Need::Optional);
  const auto* element = scenario_elements::find_element(scenario_elements::action_elements(), kind);
  auto parsed = body.is_object() ? element->read(ctx, body) : std::nullopt;
  body.finish();
  // An action with an error of its own stays out of the model (see loader_internal.hpp).
  if (!parsed || ctx.diags.error_count() != errors_before) return std::nullopt;
  return Action{std::move(*parsed), inner_description.value_or(outer_description.value_or("")), body.where()};
}

}  // namespace

std::optional<SpeedAction> read_speed_body(LoadContext& ctx, ObjectReader& r, bool needs_actor) {
  SpeedAction a;
  const auto actor = needs_actor ? r.integer("actor_id", Need::Required) : std::optional<int>(0);
  const auto type = read_speed_type(r);
  const auto target = r.integer("target_actor_id", Need::Optional);
  const auto value = r.number("value", Need::Required, Quantity::SpeedKmh);
  const auto accel = read_accel(ctx, r);
  if (!actor || !type || !value || !accel) return std::nullopt;
  a.actor = *actor;
  a.type = *type;
  a.value = kmh_to_ms(*value);
  a.accel = *accel;
  if (a.type == SpeedType::Relative) {
    a.target = target.value_or(ctx.ego_id);  // absent: relative to the ego, as in the reference
  } else if (target) {
    r.warning("target_actor_id", "\"target_actor_id\" has no effect on an absolute speed");
  }
  return a;
}

std::vector<Action> read_actions(LoadContext& ctx, const nlohmann::json& array, const std::string& pointer) {
  std::vector<Action> actions;
  for (std::size_t i = 0; i < array.size(); ++i)
    if (auto action = read_action(ctx, array[i], json_pointer_child(pointer, i))) actions.push_back(std::move(*action));
  return actions;
}

}  // namespace orch::scenario_loading
