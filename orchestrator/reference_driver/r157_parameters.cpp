#include "reference_driver/r157_parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "core/suggest.hpp"

namespace orch::reference_driver {

const std::vector<TimeGapRow>& time_gap_table() {
  // R157 paragraph 5.2.3.3 (as amended for speeds up to 130 km/h): present speed, minimum time gap.
  static const std::vector<TimeGapRow> table{{7.2, 1.0},  {10, 1.1},  {20, 1.2},  {30, 1.3},  {40, 1.4},
                                             {50, 1.5},   {60, 1.6},  {70, 1.7},  {80, 1.8},  {90, 1.9},
                                             {100, 2.0},  {110, 2.0}, {120, 2.0}, {130, 2.0}};
  return table;
}

double R157Parameters::time_gap(double speed) const {
  const auto& table = time_gap_table();
  const double kmh = speed * 3.6;
  if (kmh <= table.front().speed_kmh) return table.front().time_gap_s;
  for (std::size_t i = 1; i < table.size(); ++i) {
    if (kmh > table[i].speed_kmh) continue;
    const TimeGapRow& a = table[i - 1];
    const TimeGapRow& b = table[i];
    return a.time_gap_s + (b.time_gap_s - a.time_gap_s) * (kmh - a.speed_kmh) / (b.speed_kmh - a.speed_kmh);
  }
  return table.back().time_gap_s;
}

double R157Parameters::min_following_distance(double speed) const {
  return std::max(min_standstill_gap, std::max(0.0, speed) * time_gap(speed));
}

const std::vector<ParameterInfo>& parameter_infos() {
  static const std::vector<ParameterInfo> infos{
      {"wandering_threshold", "m", "Annex 4 App. 3 (lateral wandering distance: the risk perception point of a cut-in / cut-out)",
       &R157Parameters::wandering_threshold},
      {"risk_perception_time", "s", "Annex 4 App. 3 (risk perception time)", &R157Parameters::risk_perception_time},
      {"brake_reaction_time", "s", "Annex 4 App. 3 (time to move the foot to the brake)", &R157Parameters::brake_reaction_time},
      {"max_deceleration", "m/s^2", "Annex 4 App. 3 (0.774 G, G = 9.81 m/s^2)", &R157Parameters::max_deceleration},
      {"brake_jerk", "m/s^3", "Annex 4 App. 3 (deceleration build-up: 0.774 G in 0.6 s)", &R157Parameters::brake_jerk},
      {"wrap_deceleration", "m/s^2",
       "Annex 4 App. 3 Table 1 (after full wrap of the ego and the cut-in vehicle: 0.85 G in 0.6 s)",
       &R157Parameters::wrap_deceleration},
      {"lead_deceleration_threshold", "m/s^2", "Annex 4 App. 3 (decelerating lead vehicle: the risk perception point)",
       &R157Parameters::lead_deceleration_threshold},
      {"critical_ttc", "s", "the model's own (esmini's ReferenceDriver uses the same 2 s)", &R157Parameters::critical_ttc},
      {"min_standstill_gap", "m", "5.2.3.3 (the minimum following distance is never below 2 m)",
       &R157Parameters::min_standstill_gap},
      {"comfort_acceleration", "m/s^2", "the model's own (normal driving)", &R157Parameters::comfort_acceleration},
      {"comfort_deceleration", "m/s^2", "the model's own (normal driving)", &R157Parameters::comfort_deceleration},
      {"perception_range", "m", "the model's own (7.1.1 asks a forward range of at least 46 m)", &R157Parameters::perception_range},
      {"pedestrian_margin", "m", "the model's own (a pedestrian this close beside the ego's path is in it)",
       &R157Parameters::pedestrian_margin},
  };
  return infos;
}

void apply_overrides(R157Parameters& p, const std::map<std::string, double>& overrides) {
  std::vector<std::string> names;
  for (const auto& info : parameter_infos()) names.push_back(info.name);
  for (const auto& [key, value] : overrides) {
    const std::string& name = key;  // (a structured binding cannot be captured before C++20 in clang)
    const auto it = std::find_if(parameter_infos().begin(), parameter_infos().end(),
                                 [&name](const ParameterInfo& i) { return i.name == name; });
    if (it == parameter_infos().end())
      throw std::invalid_argument(fmt::format("unknown r157 parameter \"{}\"{}; expected one of {}", key,
                                              did_you_mean(key, names), quoted_list(names)));
    const bool may_be_zero = key == "wandering_threshold" || key == "pedestrian_margin";
    if (!(value > 0) && !(may_be_zero && value == 0))
      throw std::invalid_argument(fmt::format("r157 parameter \"{}\" must be {}, got {}", key,
                                              may_be_zero ? "0 or more" : "positive", value));
    p.*(it->field) = value;
  }
}

}  // namespace orch::reference_driver
