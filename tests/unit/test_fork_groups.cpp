// Which runs of a batch share their prefix (batch/fork_groups.hpp): same logical scenario,
// seed and settings (an OpenSCENARIO variation's too); halved while cores would idle.
#include <gtest/gtest.h>

#include "batch/fork_groups.hpp"
#include "batch/variation_batch.hpp"

using namespace orch::batch;

namespace {

BatchPlan plan_of(const std::vector<std::pair<std::size_t, long long>>& runs, std::size_t logicals = 2) {
  BatchPlan plan;
  plan.logicals.resize(logicals);
  for (const auto& [logical, seed] : runs) {
    PlannedRun r;
    r.logical_index = logical;
    r.set.seed = seed;
    plan.runs.push_back(r);
  }
  return plan;
}

std::vector<std::size_t> all(const BatchPlan& plan) {
  std::vector<std::size_t> v;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) v.push_back(i);
  return v;
}

using Groups = std::vector<std::vector<std::size_t>>;

}  // namespace

TEST(ForkGroups, RunsShareOnlyWithTheirLogicalSeedAndSettings) {
  BatchPlan plan = plan_of({{0, 1}, {0, 1}, {0, 2}, {1, 1}, {0, 1}});
  EXPECT_EQ(fork_groups(plan, all(plan), true, 1), (Groups{{0, 1, 4}, {2}, {3}}));
  plan.runs[4].set.sumo_config.max_time = 30;  // other settings: another group
  EXPECT_EQ(fork_groups(plan, all(plan), true, 1), (Groups{{0, 1}, {2}, {3}, {4}}));
  EXPECT_EQ(fork_groups(plan, {1, 4}, true, 1), (Groups{{1}, {4}}));  // only the pending runs
}

TEST(ForkGroups, DisabledRunsEveryRunAlone) {
  BatchPlan plan = plan_of({{0, 1}, {0, 1}, {1, 1}, {1, 1}});
  EXPECT_EQ(fork_groups(plan, all(plan), false, 1), (Groups{{0}, {1}, {2}, {3}}));
}

// A variation's sets differ in --param values of one file: they share like a template's.
TEST(ForkGroups, AVariationsSetsShareLikeATemplates) {
  BatchPlan plan = plan_of({{0, 1}, {0, 1}, {1, 3}, {1, 4}, {1, 3}});
  plan.logicals[1].variation = std::make_shared<VariationLogical>();
  EXPECT_EQ(fork_groups(plan, all(plan), true, 1), (Groups{{0, 1}, {2, 4}, {3}}));
  use_one_seed_per_logical(plan);  // batch --fork: the variation's first seed for all its sets
  EXPECT_EQ(plan.runs[3].set.seed, 3);
  EXPECT_EQ(fork_groups(plan, all(plan), true, 1), (Groups{{0, 1}, {2, 3, 4}}));
}

TEST(ForkGroups, OneSeedPerLogicalScenarioMakesThemShare) {
  BatchPlan plan = plan_of({{0, 5}, {0, 6}, {1, 9}, {0, 7}, {1, 10}});
  use_one_seed_per_logical(plan);
  EXPECT_EQ(plan.runs[1].set.seed, 5);
  EXPECT_EQ(plan.runs[3].set.seed, 5);
  EXPECT_EQ(plan.runs[4].set.seed, 9);
  EXPECT_EQ(fork_groups(plan, all(plan), true, 1), (Groups{{0, 1, 3}, {2, 4}}));
}

TEST(ForkGroups, FewerGroupsThanJobsHalveTheLargest) {
  const BatchPlan plan = plan_of({{0, 1}, {0, 1}, {0, 1}, {0, 1}, {0, 1}});
  EXPECT_EQ(fork_groups(plan, all(plan), true, 2), (Groups{{0, 1}, {2, 3, 4}}));
  EXPECT_EQ(fork_groups(plan, all(plan), true, 3), (Groups{{0, 1}, {2}, {3, 4}}));
  EXPECT_EQ(fork_groups(plan, all(plan), true, 9).size(), 5u);  // never below one run a group
}
