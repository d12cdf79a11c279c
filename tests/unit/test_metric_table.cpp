// The metric table (metrics/metric_table.hpp) is consistent, and what it generates keeps the
// outputs of the runs before it: metrics.csv's first columns, result.json's first summary keys
// and the criteria's first metric names, each in its earlier order.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "metrics/metric_table.hpp"

namespace orch::metrics {
namespace {

std::vector<std::string> first(const std::vector<std::string>& all, std::size_t n) {
  return std::vector<std::string>(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(std::min(n, all.size())));
}

std::vector<std::string> split(const std::string& header) {
  std::vector<std::string> out(1);
  for (const char c : header) {
    if (c == ',') {
      out.emplace_back();
    } else {
      out.back().push_back(c);
    }
  }
  return out;
}

TEST(MetricTable, EveryEntryIsComplete) {
  std::set<std::string_view> names, keys, columns{"time", "actor_id"};
  for (const MetricDef& d : metric_table()) {
    EXPECT_EQ(d.name.empty(), d.value == nullptr) << d.name << ": a name exactly when there is a value per step";
    if (!d.name.empty()) {
      EXPECT_TRUE(names.insert(d.name).second) << "name twice: " << d.name;
    }
    EXPECT_EQ(d.summary == Summary::None, d.summary_key.empty()) << d.name << ": a summary has its key";
    if (d.summary != Summary::None) {
      EXPECT_TRUE(keys.insert(d.summary_key).second) << "key twice: " << d.summary_key;
    }
    EXPECT_EQ(d.summary == Summary::OverRun, d.over_run != nullptr) << d.summary_key;
    if (d.summary != Summary::None && d.summary != Summary::OverRun) {
      EXPECT_TRUE(d.value != nullptr) << d.summary_key << " folds the values per step";
    }
    for (const Column& c : d.columns) {
      EXPECT_TRUE(columns.insert(c.name).second) << "column twice: " << c.name;
      EXPECT_TRUE(c.cell == Cell::Partner ? d.partner != nullptr : d.value != nullptr) << c.name;
    }
  }
}

TEST(MetricTable, EverySummaryOnceInResultJson) {
  std::vector<std::size_t> rows = summary_rows();
  std::size_t with_summary = 0;
  for (const MetricDef& d : metric_table()) with_summary += d.summary != Summary::None;
  EXPECT_EQ(rows.size(), with_summary);
  std::sort(rows.begin(), rows.end());
  EXPECT_EQ(std::adjacent_find(rows.begin(), rows.end()), rows.end());
}

TEST(MetricTable, TheEarlierOutputsKeepTheirOrder) {
  EXPECT_EQ(first(split(metrics_csv_header()), 14),
            (std::vector<std::string>{"time", "actor_id", "leader", "gap", "rel_speed", "ttc", "thw", "drac", "accel",
                                      "jerk", "lat_accel", "lane_departure", "min_dist", "min_dist_to"}));
  std::vector<std::string> keys;
  for (const std::size_t i : summary_rows()) keys.emplace_back(metric_table()[i].summary_key);
  EXPECT_EQ(first(keys, 14),
            (std::vector<std::string>{"min_ttc", "min_thw", "min_gap", "max_drac", "min_follower_ttc",
                                      "min_follower_thw", "min_dist", "min_pet", "max_decel", "max_abs_jerk",
                                      "max_lat_accel", "max_speed", "standstill_time", "lane_departure_time"}));
  std::vector<std::string> names(metric_names().begin(), metric_names().end());
  EXPECT_EQ(first(names, 17),
            (std::vector<std::string>{"speed", "gap", "rel_speed", "ttc", "thw", "drac", "follower_gap",
                                      "follower_ttc", "follower_thw", "accel", "decel", "jerk", "lat_accel",
                                      "yaw_rate", "standstill", "lane_departure", "min_dist"}));
}

TEST(MetricTable, SummariesFoldAsTheirKindSays) {
  ActorSummary s;
  ActorMetrics m;
  m.time = 1;
  m.speed = 10;
  m.kinematics.jerk = -4;  // |jerk| 4
  m.min_dist = 3;
  m.min_dist_to = "bg.1";
  s.add(m, 0.1);
  m.time = 2;
  m.speed = 12;
  m.kinematics.jerk = 2;
  m.min_dist = 5;
  m.min_dist_to = "bg.2";
  s.add(m, 0.1);
  EXPECT_DOUBLE_EQ(s.extreme("max_speed")->value, 12);
  EXPECT_DOUBLE_EQ(s.extreme("max_abs_jerk")->value, 4);
  EXPECT_DOUBLE_EQ(s.extreme("max_abs_jerk")->time, 1);
  EXPECT_EQ(s.extreme("min_dist")->partner, "bg.1");
  EXPECT_FALSE(s.extreme("min_pet")) << "PET comes from the trajectories at the end, not per step";
}

TEST(MetricTable, FollowerDracIsTheLastColumnKeyAndName) {
  EXPECT_EQ(split(metrics_csv_header()).back(), "follower_drac");
  EXPECT_EQ(metric_table()[summary_rows().back()].summary_key, "max_follower_drac");
  EXPECT_EQ(metric_names().back(), "follower_drac");
}

}  // namespace
}  // namespace orch::metrics
