#include "metrics/actor_metrics.hpp"

#include <cmath>
#include <stdexcept>

#include "metrics/metric_table.hpp"

namespace orch::metrics {

namespace {

const MetricDef* step_metric(std::string_view name) {
  for (const MetricDef& d : metric_table())
    if (d.value && d.name == name) return &d;
  return nullptr;
}

void keep_min(std::optional<Extreme>& e, double v, double time, std::string_view partner) {
  if (!e || v < e->value) e = Extreme{v, time, std::string(partner)};
}
void keep_max(std::optional<Extreme>& e, double v, double time, std::string_view partner) {
  if (!e || v > e->value) e = Extreme{v, time, std::string(partner)};
}

std::size_t summary_row(std::string_view key) {
  const auto& table = metric_table();
  for (std::size_t i = 0; i < table.size(); ++i)
    if (table[i].summary != Summary::None && table[i].summary_key == key) return i;
  throw std::invalid_argument("no metric summary " + std::string(key));
}

}  // namespace

const std::vector<std::string_view>& metric_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> out;
    for (const MetricDef& d : metric_table())
      if (d.value) out.push_back(d.name);
    return out;
  }();
  return names;
}

std::optional<double> metric_value(const ActorMetrics& m, std::string_view name) {
  const MetricDef* d = step_metric(name);
  return d ? d->value(m) : std::nullopt;
}

std::string metric_partner(const ActorMetrics& m, std::string_view name) {
  const MetricDef* d = step_metric(name);
  return d && d->partner ? std::string(d->partner(m)) : std::string{};
}

ActorSummary::ActorSummary() : rows(metric_table().size()) {}

void ActorSummary::add(const ActorMetrics& m, double dt) {
  const auto& table = metric_table();
  for (std::size_t i = 0; i < table.size(); ++i) {
    const MetricDef& d = table[i];
    if (!d.value || d.summary == Summary::None || d.summary == Summary::OverRun) continue;
    const std::optional<double> v = d.value(m);
    if (!v) continue;
    Row& row = rows[i];
    const std::string_view partner = d.partner ? d.partner(m) : std::string_view{};
    switch (d.summary) {
      case Summary::Min: keep_min(row.extreme, *v, m.time, partner); break;
      case Summary::Max: keep_max(row.extreme, *v, m.time, partner); break;
      case Summary::MaxAbs: keep_max(row.extreme, std::abs(*v), m.time, partner); break;
      case Summary::SecondsPositive:
        if (*v > 0) row.seconds += dt;
        break;
      case Summary::None:
      case Summary::OverRun: break;
    }
  }
}

const std::optional<Extreme>& ActorSummary::extreme(std::string_view key) const {
  static const std::optional<Extreme> none;
  const std::size_t i = summary_row(key);
  return i < rows.size() ? rows[i].extreme : none;
}

double ActorSummary::seconds(std::string_view key) const {
  const std::size_t i = summary_row(key);
  return i < rows.size() ? rows[i].seconds : 0.0;
}

}  // namespace orch::metrics
