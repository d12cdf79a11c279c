#include "metrics/metric_table.hpp"

#include <array>
#include <stdexcept>

#include "metrics/pet.hpp"

namespace orch::metrics {

namespace {

using Value = std::optional<double>;

// The leader's and the follower's measures (metrics/following.*).
std::string_view leader(const ActorMetrics& m) { return m.leader ? std::string_view(m.leader->other) : ""; }
std::string_view follower(const ActorMetrics& m) { return m.follower ? std::string_view(m.follower->other) : ""; }
template <auto Field>
Value of_leader(const ActorMetrics& m) {
  if (!m.leader) return std::nullopt;
  return (*m.leader).*Field;
}
template <auto Field>
Value of_follower(const ActorMetrics& m) {
  if (!m.follower) return std::nullopt;
  return (*m.follower).*Field;
}
std::string_view nearest(const ActorMetrics& m) { return m.min_dist_to; }

std::optional<Extreme> min_pet(const TrajectoryBook& book, const std::string& id) {
  const auto pet = book.min_pet(id);
  if (!pet) return std::nullopt;
  return Extreme{pet->pet.pet, pet->pet.time, pet->partner};
}

// The table. A new metric is one entry at the end (docs/layout.md "Adding a metric"): its column,
// summary key and name then come after every earlier one.
std::vector<MetricDef> make_table() {
  return {
    {.name = "speed", .value = [](const ActorMetrics& m) -> Value { return m.speed; },
     .summary = Summary::Max, .summary_key = "max_speed"},
    {.name = "gap", .value = of_leader<&Following::gap>, .partner = leader,
     .columns = {{"leader", Cell::Partner}, {"gap"}}, .summary = Summary::Min, .summary_key = "min_gap"},
    {.name = "rel_speed", .value = of_leader<&Following::rel_speed>, .partner = leader, .columns = {{"rel_speed"}}},
    {.name = "ttc", .value = of_leader<&Following::ttc>, .partner = leader, .columns = {{"ttc"}},
     .summary = Summary::Min, .summary_key = "min_ttc"},
    {.name = "thw", .value = of_leader<&Following::thw>, .partner = leader, .columns = {{"thw"}},
     .summary = Summary::Min, .summary_key = "min_thw"},
    {.name = "drac", .value = of_leader<&Following::drac>, .partner = leader, .columns = {{"drac"}},
     .summary = Summary::Max, .summary_key = "max_drac"},
    {.name = "follower_gap", .value = of_follower<&Following::gap>, .partner = follower},
    {.name = "follower_ttc", .value = of_follower<&Following::ttc>, .partner = follower,
     .summary = Summary::Min, .summary_key = "min_follower_ttc"},
    {.name = "follower_thw", .value = of_follower<&Following::thw>, .partner = follower,
     .summary = Summary::Min, .summary_key = "min_follower_thw"},
    {.name = "accel", .value = [](const ActorMetrics& m) { return m.kinematics.accel; }, .columns = {{"accel"}}},
    {.name = "decel",
     .value = [](const ActorMetrics& m) { return m.kinematics.accel ? Value(-*m.kinematics.accel) : std::nullopt; },
     .summary = Summary::Max, .summary_key = "max_decel"},
    {.name = "jerk", .value = [](const ActorMetrics& m) { return m.kinematics.jerk; }, .columns = {{"jerk"}},
     .summary = Summary::MaxAbs, .summary_key = "max_abs_jerk"},
    {.name = "lat_accel", .value = [](const ActorMetrics& m) { return m.kinematics.lat_accel; },
     .columns = {{"lat_accel"}}, .summary = Summary::MaxAbs, .summary_key = "max_lat_accel"},
    {.name = "yaw_rate", .value = [](const ActorMetrics& m) { return m.kinematics.yaw_rate; }},
    {.name = "standstill", .value = [](const ActorMetrics& m) -> Value { return m.kinematics.standstill; },
     .summary = Summary::SecondsPositive, .summary_key = "standstill_time"},
    {.name = "lane_departure", .value = [](const ActorMetrics& m) { return m.lane_departure; },
     .columns = {{"lane_departure"}}, .summary = Summary::SecondsPositive, .summary_key = "lane_departure_time"},
    {.name = "min_dist", .value = [](const ActorMetrics& m) { return m.min_dist; }, .partner = nearest,
     .columns = {{"min_dist"}, {"min_dist_to", Cell::Partner}}, .summary = Summary::Min, .summary_key = "min_dist"},
    {.summary = Summary::OverRun, .summary_key = "min_pet", .over_run = min_pet},
    // The deceleration the follower needs not to run into the actor (docs/evaluation.md): its
    // largest value is the worst case.
    {.name = "follower_drac", .value = of_follower<&Following::drac>, .partner = follower,
     .columns = {{"follower_drac"}}, .summary = Summary::Max, .summary_key = "max_follower_drac"},
  };
}

// result.json listed the summaries in this order before the table existed; the order is kept so
// that a run's result.json stays byte-identical. Later summaries follow in table order: do not
// add to this list.
constexpr std::array<std::string_view, 14> kEarlierSummaryOrder{
    "min_ttc",   "min_thw",   "min_gap",      "max_drac",      "min_follower_ttc", "min_follower_thw", "min_dist",
    "min_pet",   "max_decel", "max_abs_jerk", "max_lat_accel", "max_speed",        "standstill_time",
    "lane_departure_time"};

}  // namespace

const std::vector<MetricDef>& metric_table() {
  static const std::vector<MetricDef> table = make_table();
  return table;
}

const std::vector<std::size_t>& summary_rows() {
  static const std::vector<std::size_t> rows = [] {
    const auto& table = metric_table();
    std::vector<std::size_t> out;
    std::vector<bool> placed(table.size(), false);
    for (const std::string_view key : kEarlierSummaryOrder) {
      std::size_t i = 0;
      while (i < table.size() && !(table[i].summary != Summary::None && table[i].summary_key == key)) ++i;
      if (i == table.size()) throw std::logic_error("metric table: no summary " + std::string(key));
      out.push_back(i);
      placed[i] = true;
    }
    for (std::size_t i = 0; i < table.size(); ++i)
      if (table[i].summary != Summary::None && !placed[i]) out.push_back(i);
    return out;
  }();
  return rows;
}

std::string metrics_csv_header() {
  std::string header = "time,actor_id";
  for (const MetricDef& d : metric_table())
    for (const Column& c : d.columns) {
      header += ',';
      header += c.name;
    }
  return header;
}

}  // namespace orch::metrics
