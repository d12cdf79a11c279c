// Every criterion type and mode on hand-made step values.
#include <gtest/gtest.h>

#include <set>

#include "run/criteria_judge.hpp"
#include "criteria/criterion.hpp"
#include "run/run_result.hpp"

namespace orch::criteria {
namespace {

struct FakeRun {
  std::vector<engine::SceneVisit> visits{{0, "", 0}};
  std::vector<engine::Contact> contacts;
  int scene = 0;
  bool ending = false;
};

// Feeds `values` (one per 0.1 s step, nullopt = not measured) of metric `ttc` into a criterion.
CriterionState judge(CriterionSpec spec, const std::vector<std::optional<double>>& values, FakeRun run = {}) {
  CriterionState state(std::move(spec), 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    metrics::ActorMetrics m;
    m.time = 0.1 * static_cast<double>(i + 1);
    if (values[i]) m.leader = metrics::following_measures("1", *values[i], 1, 0);  // ttc = gap / 1
    const RunFacts facts{m.time, run.scene, run.ending, run.visits, run.contacts};
    state.step(facts, &m);
  }
  return state;
}

CriterionSpec ttc_min(double min, Mode mode = Mode::AllOf) {
  CriterionSpec s;
  s.name = "ttc";
  s.metric = "ttc";
  s.min = min;
  s.mode = mode;
  return s;
}

TEST(Criteria, AllOfFailsAndReportsTheWorstValue) {
  const auto r = judge(ttc_min(2), {5.0, 3.0, 1.5, 1.0, 4.0}).result();
  EXPECT_FALSE(r.success);
  EXPECT_DOUBLE_EQ(*r.actual, 1.0);  // the minimum TTC, when it happened
  EXPECT_NEAR(*r.at_time, 0.4, 1e-9);
  EXPECT_EQ(r.expected, "ttc >= 2 at every step");
  EXPECT_EQ(r.metric, "ttc");
  EXPECT_EQ(*r.actor, 0);
}

TEST(Criteria, AllOfHoldsAndReportsTheWorstValue) {
  const auto r = judge(ttc_min(2), {5.0, std::nullopt, 2.5, 4.0}).result();
  EXPECT_TRUE(r.success);
  EXPECT_DOUBLE_EQ(*r.actual, 2.5);
  EXPECT_NEAR(*r.at_time, 0.3, 1e-9);
}

TEST(Criteria, AllOfWithNothingMeasuredHolds) {
  const auto r = judge(ttc_min(2), {std::nullopt, std::nullopt}).result();
  EXPECT_TRUE(r.success);
  EXPECT_FALSE(r.actual);
}

TEST(Criteria, AnyOfNeedsOneStepWithin) {
  CriterionSpec s = ttc_min(0);
  s.min.reset();
  s.max = 2;  // "ttc <= 2 at some step"
  s.mode = Mode::AnyOf;
  const auto hit = judge(s, {5.0, 1.9, 4.0, 1.5}).result();
  EXPECT_TRUE(hit.success);
  EXPECT_DOUBLE_EQ(*hit.actual, 1.5);  // the best value
  EXPECT_NEAR(*hit.at_time, 0.4, 1e-9);
  const auto miss = judge(s, {5.0, 2.5, 4.0}).result();
  EXPECT_FALSE(miss.success);
  EXPECT_DOUBLE_EQ(*miss.actual, 2.5);  // the closest it came
}

TEST(Criteria, PassRateCountsMeasuredSteps) {
  CriterionSpec s = ttc_min(2, Mode::PassRate);
  s.pass_rate = 75;
  const auto r = judge(s, {5.0, 1.0, 3.0, std::nullopt, 4.0}).result();  // 3 of 4 measured within
  EXPECT_TRUE(r.success);
  EXPECT_DOUBLE_EQ(*r.actual, 75);
  s.pass_rate = 80;
  EXPECT_FALSE(judge(s, {5.0, 1.0, 3.0, std::nullopt, 4.0}).holds());
}

TEST(Criteria, DurationIsTheLongestStretchOutside) {
  CriterionSpec s = ttc_min(2, Mode::Duration);
  s.duration = 0.25;
  // outside at steps 2-3 (0.2 s) and 5-7 (0.3 s): the longest lasts 0.3 s from t = 0.5
  const auto r = judge(s, {5.0, 1.0, 1.0, 3.0, 1.0, 1.0, 1.0, 3.0}).result();
  EXPECT_FALSE(r.success);
  EXPECT_NEAR(*r.actual, 0.3, 1e-9);
  EXPECT_NEAR(*r.at_time, 0.5, 1e-9);
  s.duration = 0.3;
  EXPECT_TRUE(judge(s, {5.0, 1.0, 1.0, 3.0, 1.0, 1.0, 1.0, 3.0}).holds());
}

TEST(Criteria, TimeWindowLimitsTheSteps) {
  CriterionSpec s = ttc_min(2);
  s.from_time = 0.25;  // from the third step on
  EXPECT_TRUE(judge(s, {1.0, 1.0, 3.0, 4.0}).holds());
  s.to_time = 0.35;
  EXPECT_TRUE(judge(s, {1.0, 1.0, 3.0, 1.0}).holds());
  s.to_time = 0.45;
  EXPECT_FALSE(judge(s, {1.0, 1.0, 3.0, 1.0}).holds());
}

TEST(Criteria, SceneWindowFromEnteringUntilEntering) {
  CriterionSpec spec = ttc_min(2);
  spec.from_scene = 1;
  spec.to_scene = 2;
  CriterionState state(spec, 0);
  FakeRun run;
  const std::vector<std::pair<int, double>> steps{{0, 1.0}, {1, 3.0}, {1, 2.5}, {2, 1.0}, {1, 1.0}};
  for (std::size_t i = 0; i < steps.size(); ++i) {
    metrics::ActorMetrics m;
    m.time = 0.1 * static_cast<double>(i + 1);
    m.leader = metrics::following_measures("1", steps[i].second, 1, 0);
    state.step(RunFacts{m.time, steps[i].first, false, run.visits, run.contacts}, &m);
  }
  // scene 0's 1.0 and everything after entering scene 2 (even back in 1) do not count
  EXPECT_TRUE(state.holds());
  EXPECT_DOUBLE_EQ(*state.result().actual, 2.5);
}

TEST(Criteria, NoCollisionWithWhomAndCountedOnly) {
  FakeRun run;
  run.contacts.push_back({1.0, "0", "bg.3", {0, 0}, {0, 0}, "geometry", "", true});
  run.contacts.push_back({2.0, "1", "0", {0, 0}, {0, 0}, "sumo", "collision", false});  // not counted
  CriterionSpec any;
  any.name = "nc";
  any.type = "no_collision";
  const auto r = judge(any, {std::nullopt}, run).result();
  EXPECT_FALSE(r.success);
  EXPECT_DOUBLE_EQ(*r.actual, 1);
  EXPECT_EQ(r.metric, "collisions");
  CriterionSpec with_1 = any;
  with_1.with = {"1"};
  EXPECT_TRUE(judge(with_1, {std::nullopt}, run).holds());
  with_1.with = {"bg.3"};
  EXPECT_FALSE(judge(with_1, {std::nullopt}, run).holds());
}

TEST(Criteria, ReachSceneAnEndingOrAGivenOne) {
  CriterionSpec s;
  s.name = "end";
  s.type = "reach_scene";
  s.mode = Mode::AnyOf;
  FakeRun run;
  EXPECT_FALSE(judge(s, {std::nullopt}, run).holds());
  run.ending = true;
  EXPECT_TRUE(judge(s, {std::nullopt}, run).holds());
  s.scene = 3;
  EXPECT_FALSE(judge(s, {std::nullopt}, run).holds());
  run.visits.push_back({3, "", 1.0});
  EXPECT_TRUE(judge(s, {std::nullopt}, run).holds());
}

TEST(Criteria, MaxSpeedStandstillKeepLane) {
  FakeRun run;
  auto one = [&](CriterionSpec s, metrics::ActorMetrics m) {
    CriterionState state(std::move(s), 0);
    state.step(RunFacts{0.1, 0, false, run.visits, run.contacts}, &m);
    return state.result();
  };
  metrics::ActorMetrics m;
  m.speed = 31;
  m.kinematics.standstill = 12;
  m.lane_departure = 0.2;
  CriterionSpec speed;
  speed.name = "v";
  speed.type = "max_speed";
  speed.max = 30;
  EXPECT_FALSE(one(speed, m).success);
  EXPECT_EQ(one(speed, m).metric, "speed");
  CriterionSpec still;
  still.name = "still";
  still.type = "standstill";
  still.max = 10;
  EXPECT_FALSE(one(still, m).success);
  still.max = 15;
  EXPECT_TRUE(one(still, m).success);
  CriterionSpec lane;
  lane.name = "lane";
  lane.type = "keep_lane";
  lane.max = 0;
  EXPECT_FALSE(one(lane, m).success);
  lane.max = 0.25;
  EXPECT_TRUE(one(lane, m).success);
}

TEST(Criteria, VerdictNamesEveryFailingCriterion) {
  RunResult r;
  r.verdict = Verdict::Success;
  r.reason = "ending scene 3 reached";
  r.criteria.push_back({"min_ttc", 0, "ttc", "ttc >= 2 at every step", 1.5, 12.35, false});
  r.criteria.push_back({"end", 0, "scene", "reach an ending scene", 1, 20, true});
  r.criteria.push_back({"brake", 0, "decel", "decel <= 5 at every step", 6.25, 13.0, false});
  apply_criteria(r);
  EXPECT_EQ(r.verdict, Verdict::Failure);
  EXPECT_EQ(r.reason,
            "criteria failed: min_ttc: expected ttc >= 2 at every step, actual 1.500 at t=12.35 s; brake: expected "
            "decel <= 5 at every step, actual 6.250 at t=13.00 s (ending scene 3 reached)");
  RunResult error;
  error.verdict = Verdict::Error;
  error.criteria = r.criteria;
  apply_criteria(error);
  EXPECT_EQ(error.verdict, Verdict::Error);
}

TEST(Criteria, EveryTypeHasAUniqueName) {
  std::set<std::string_view> names;
  for (const auto& t : criterion_types()) EXPECT_TRUE(names.insert(t.name).second) << t.name;
  EXPECT_TRUE(find_criterion_type("no_collision"));
  EXPECT_FALSE(find_criterion_type("no_colision"));
}

}  // namespace
}  // namespace orch::criteria
