#include "batch/fork_groups.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <string>
#include <tuple>

namespace orch::batch {

namespace {

// Runs share when their logical scenario, seed and run settings are the same.
std::string share_key(const PlannedRun& run) {
  const SumoConfig& c = run.set.sumo_config;
  return fmt::format("{}|{}|{}|{}|{}|{}|{}", run.logical_index, run.set.seed.value_or(42), c.step,
                     c.max_time ? fmt::format("{}", *c.max_time) : "-", c.traffic.value_or("-"),
                     c.backend.value_or("-"), c.map);
}

}  // namespace

void use_one_seed_per_logical(BatchPlan& plan) {
  std::map<std::size_t, std::optional<long long>> first_seed;
  for (auto& run : plan.runs) {
    const auto [it, added] = first_seed.emplace(run.logical_index, run.set.seed);
    if (!added) run.set.seed = it->second;
  }
}

std::vector<std::vector<std::size_t>> fork_groups(const BatchPlan& plan, const std::vector<std::size_t>& pending,
                                                  bool enabled, int jobs) {
  std::vector<std::vector<std::size_t>> groups;
  std::map<std::string, std::size_t> group_of;
  for (const auto i : pending) {
    const PlannedRun& run = plan.runs[i];
    if (!enabled) {
      groups.push_back({i});
      continue;
    }
    const auto [it, added] = group_of.emplace(share_key(run), groups.size());
    if (added) groups.emplace_back();
    groups[it->second].push_back(i);
  }
  while (static_cast<int>(groups.size()) < jobs) {
    const auto largest = std::max_element(groups.begin(), groups.end(),
                                          [](const auto& a, const auto& b) { return a.size() < b.size(); });
    if (largest == groups.end() || largest->size() < 2) break;
    const auto half = static_cast<std::ptrdiff_t>(largest->size() / 2);
    std::vector<std::size_t> second(largest->begin() + half, largest->end());
    largest->erase(largest->begin() + half, largest->end());
    groups.push_back(std::move(second));
  }
  return groups;
}

}  // namespace orch::batch
