#include "metrics/actor_metrics.hpp"

#include <cmath>

namespace orch::metrics {

namespace {
std::optional<double> leader_value(const std::optional<Following>& f, std::string_view what) {
  if (!f) return std::nullopt;
  if (what == "gap") return f->gap;
  if (what == "rel_speed") return f->rel_speed;
  if (what == "ttc") return f->ttc;
  if (what == "thw") return f->thw;
  return f->drac;
}

void keep_min(std::optional<Extreme>& e, std::optional<double> v, double time, const std::string& partner) {
  if (v && (!e || *v < e->value)) e = Extreme{*v, time, partner};
}
void keep_max(std::optional<Extreme>& e, std::optional<double> v, double time, const std::string& partner) {
  if (v && (!e || *v > e->value)) e = Extreme{*v, time, partner};
}
}  // namespace

const std::vector<std::string_view>& metric_names() {
  static const std::vector<std::string_view> names{
      "speed",        "gap",          "rel_speed", "ttc",      "thw",       "drac",          "follower_gap",
      "follower_ttc", "follower_thw", "accel",     "decel",    "jerk",      "lat_accel",     "yaw_rate",
      "standstill",   "lane_departure", "min_dist"};
  return names;
}

std::optional<double> metric_value(const ActorMetrics& m, std::string_view name) {
  if (name == "speed") return m.speed;
  if (name.starts_with("follower_")) return leader_value(m.follower, name.substr(9));
  if (name == "gap" || name == "rel_speed" || name == "ttc" || name == "thw" || name == "drac")
    return leader_value(m.leader, name);
  const Kinematics& k = m.kinematics;
  if (name == "accel") return k.accel;
  if (name == "decel") return k.accel ? std::optional<double>(-*k.accel) : std::nullopt;
  if (name == "jerk") return k.jerk;
  if (name == "lat_accel") return k.lat_accel;
  if (name == "yaw_rate") return k.yaw_rate;
  if (name == "standstill") return k.standstill;
  if (name == "lane_departure") return m.lane_departure;
  if (name == "min_dist") return m.min_dist;
  return std::nullopt;
}

std::string metric_partner(const ActorMetrics& m, std::string_view name) {
  if (name.starts_with("follower_")) return m.follower ? m.follower->other : "";
  if (name == "gap" || name == "rel_speed" || name == "ttc" || name == "thw" || name == "drac")
    return m.leader ? m.leader->other : "";
  if (name == "min_dist") return m.min_dist_to;
  return "";
}

void ActorSummary::add(const ActorMetrics& m, double dt) {
  const std::string lead = m.leader ? m.leader->other : "";
  const std::string follow = m.follower ? m.follower->other : "";
  keep_min(min_ttc, metric_value(m, "ttc"), m.time, lead);
  keep_min(min_thw, metric_value(m, "thw"), m.time, lead);
  keep_min(min_gap, metric_value(m, "gap"), m.time, lead);
  keep_max(max_drac, metric_value(m, "drac"), m.time, lead);
  keep_min(min_follower_ttc, metric_value(m, "follower_ttc"), m.time, follow);
  keep_min(min_follower_thw, metric_value(m, "follower_thw"), m.time, follow);
  keep_min(min_dist, m.min_dist, m.time, m.min_dist_to);
  keep_max(max_decel, metric_value(m, "decel"), m.time, "");
  const auto jerk = m.kinematics.jerk;
  keep_max(max_abs_jerk, jerk ? std::optional<double>(std::abs(*jerk)) : std::nullopt, m.time, "");
  const auto lat = m.kinematics.lat_accel;
  keep_max(max_lat_accel, lat ? std::optional<double>(std::abs(*lat)) : std::nullopt, m.time, "");
  keep_max(max_speed, m.speed, m.time, "");
  if (m.kinematics.standstill > 0) standstill_time += dt;
  if (m.lane_departure && *m.lane_departure > 0) lane_departure_time += dt;
}

}  // namespace orch::metrics
