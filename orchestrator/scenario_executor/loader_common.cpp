// Small readers the scenario loader uses everywhere: comparisons, enums, waypoint
// references, id strings and id lists.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/suggest.hpp"
#include "json/json_text.hpp"
#include "scenario_executor/elements.hpp"
#include "scenario_executor/loader_internal.hpp"

namespace orch::scenario_loading {

using namespace orch::scenario;

const std::vector<std::string>& condition_kinds() {
  static const std::vector<std::string> names = scenario_elements::element_names(scenario_elements::condition_elements());
  return names;
}
const std::vector<std::string>& action_kinds() {
  static const std::vector<std::string> names = scenario_elements::element_names(scenario_elements::action_elements());
  return names;
}

std::optional<Comparison> read_comparison(ObjectReader& r, Need need) {
  static const std::vector<std::pair<std::string, Comparison>> kComparisons = {
      {">", Comparison::Greater},
      {">=", Comparison::GreaterEqual},
      {"=", Comparison::Equal},
      {"<=", Comparison::LessEqual},
      {"<", Comparison::Less}};
  const auto text = r.string("comparison", need);
  if (!text) return std::nullopt;
  for (const auto& [spelling, comparison] : kComparisons)
    if (*text == spelling) return comparison;
  // Spellings from other languages: edit distance would propose ">" for "=>".
  static const std::vector<std::pair<std::string, std::string>> kForeign = {
      {"=>", ">="}, {"=<", "<="}, {"==", "="}, {"!=", ""}, {"<>", ""}};
  std::string hint;
  for (const auto& [foreign, ours] : kForeign)
    if (*text == foreign && !ours.empty()) hint = fmt::format(" (did you mean \"{}\"?)", ours);
  if (hint.empty() && std::none_of(kForeign.begin(), kForeign.end(),
                                   [&](const auto& f) { return f.first == *text; }))
    hint = did_you_mean(*text, {">", ">=", "=", "<=", "<"});
  r.error("comparison",
          fmt::format("\"comparison\" is \"{}\", expected \">\", \">=\", \"=\", \"<=\" or \"<\"{}", *text, hint));
  return std::nullopt;
}

std::optional<MeasureType> read_measure_type(ObjectReader& r) {
  const auto text = r.choice("measure_type", {"center", "surface"}, Need::Optional);
  if (!r.has("measure_type")) return MeasureType::Center;  // the reference's default
  if (!text) return std::nullopt;
  return *text == "surface" ? MeasureType::Surface : MeasureType::Center;
}

std::optional<SpeedType> read_speed_type(ObjectReader& r) {
  const auto text = r.choice("type", {"absolute", "relative"}, Need::Required);
  if (!text) return std::nullopt;
  return *text == "relative" ? SpeedType::Relative : SpeedType::Absolute;
}

std::optional<std::string> read_id_string(ObjectReader& r, const std::string& key, Need need) {
  auto text = r.string(key, need);
  if (text && text->empty()) {
    r.error(key, fmt::format("\"{}\" must not be empty", key));
    return std::nullopt;
  }
  return text;
}

std::optional<WaypointRef> read_waypoint_ref(ObjectReader& r) {
  const auto wp_id = read_id_string(r, "wp_id", Need::Required);
  const auto wp_idx = r.number("wp_idx", Need::Required);
  if (!wp_id || !wp_idx) return std::nullopt;
  return WaypointRef{*wp_id, *wp_idx, r.where()};
}

std::vector<int> read_int_list(LoadContext& ctx, const nlohmann::json& array, const std::string& pointer,
                               const std::string& what) {
  std::vector<int> out;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const auto& item = array[i];
    const std::string item_pointer = json_pointer_child(pointer, i);
    const double d = item.is_number() ? item.get<double>() : 0.5;  // 0.5: fails the test below
    if (!ctx.need(std::floor(d) == d && std::abs(d) <= 2e9)) {
      ctx.diags.error(ctx.doc.where(item_pointer),
                      fmt::format("each entry of {} must be a whole number (a scene_id), found {}", what,
                                  item.is_number() ? json_text(item) : json_type_name(item)));
      continue;
    }
    out.push_back(static_cast<int>(d));
  }
  return out;
}

void reject_key(ObjectReader& r, const std::string& key, const std::string& why) {
  r.already_reported({key});  // with a better message than "unknown key", and not listed as allowed
  if (r.has(key)) r.error(key, why);
}

}  // namespace orch::scenario_loading
