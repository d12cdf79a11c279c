// The pure logic of `orchestrator search` (batch/search_proposal.hpp, gaussian_process.hpp,
// search_space.hpp, search_objective.hpp) on analytic functions with fixed seeds: a known
// minimum, a known pass/fail boundary, and the parameter space's errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "batch/gaussian_process.hpp"
#include "batch/search_objective.hpp"
#include "batch/search_proposal.hpp"
#include "batch/search_space.hpp"
#include "core/errors.hpp"
#include "json/json_document.hpp"

using namespace orch;
using namespace orch::batch;
using ::testing::HasSubstr;

namespace {

const SnapPoint kNoSnap = [](const Point& p) { return p; };

// A smooth bowl with its minimum 0 at (0.3, 0.7) and a second, shallower dip.
double bowl(const Point& p) {
  const double a = (p[0] - 0.3) * (p[0] - 0.3) + (p[1] - 0.7) * (p[1] - 0.7);
  const double b = (p[0] - 0.8) * (p[0] - 0.8) + (p[1] - 0.2) * (p[1] - 0.2);
  return 2.0 * a - 0.6 * std::exp(-b / 0.02) + 0.0 * b;
}
double bowl_min() {  // on a fine lattice
  double m = 1e9;
  for (int i = 0; i <= 400; ++i)
    for (int j = 0; j <= 400; ++j) m = std::min(m, bowl({i / 400.0, j / 400.0}));
  return m;
}

// Criticality monotone in one parameter (the minimum on the face y = 1) and not in the other:
// the minimum at x = 0.2, the nearest corner (0, 1) 0.03 above it.
double face_minimum(const Point& p) { return 0.6 * std::pow(1 - p[1], 1.5) + 0.75 * (p[0] - 0.2) * (p[0] - 0.2); }
// The minimum in the middle of an edge, every corner far above it.
double edge_minimum(const Point& p) {
  return 0.6 * (1 - p[1]) * (1 - p[1]) + 0.3 * (1 - p[1]) + 0.8 * (p[0] - 0.6) * (p[0] - 0.6);
}
// A narrow diagonal valley inside the box (no help from the faces).
double valley(const Point& p) {
  const double u = p[0] - 0.65, v = p[1] - 0.3;
  return 3 * (u + v) * (u + v) + 0.3 * (u - v) * (u - v);
}

// Passes outside a circle of radius 0.3 around (0.5, 0.4).
bool outside_circle(const Point& p) { return std::hypot(p[0] - 0.5, p[1] - 0.4) > 0.3; }

double misclassified(const std::vector<Point>& x, const std::vector<bool>& pass, bool sparse_grid) {
  const BoundaryEstimate b = sparse_grid ? estimate_boundary(x, pass, 41, kNoSnap) : estimate_boundary_gp(x, pass, 41);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < b.lattice.size(); ++i) wrong += b.pass[i] != outside_circle(b.lattice[i]);
  return static_cast<double>(wrong) / static_cast<double>(b.lattice.size());
}

// Runs the loop of search_runner.cpp on a function: the corners, then batches of 2; the values
// in the order the points were proposed.
std::vector<double> search_values(const std::function<double(const Point&)>& f, std::uint64_t seed, std::size_t budget) {
  SearchRng rng(seed);
  std::vector<Point> x;
  std::vector<double> y;
  for (const auto& p : initial_design(initial_design_size(2, 2), 2, rng, kNoSnap)) {
    x.push_back(p.point);
    y.push_back(f(p.point));
  }
  while (x.size() < budget)
    for (const auto& p : propose_minimum(x, y, 2, rng, kNoSnap)) {
      x.push_back(p.point);
      y.push_back(f(p.point));
    }
  return y;
}
double search_minimum(std::uint64_t seed, std::size_t budget) {
  const std::vector<double> y = search_values(bowl, seed, budget);
  return *std::min_element(y.begin(), y.end());
}

// The proof's measure (scripts/bench/search_vs_random.py) on a function: the value below which
// a fraction `p` of the box lies (on a 201 x 201 lattice), and the runs the search needs to
// get there, averaged over seeds 1..5; uniform random sampling needs 1 / p on average.
double mean_runs_to_fraction(const std::function<double(const Point&)>& f, double p) {
  std::vector<double> all;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) all.push_back(f({i / 200.0, j / 200.0}));
  std::sort(all.begin(), all.end());
  const double target = all[static_cast<std::size_t>(p * static_cast<double>(all.size()))];
  double total = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<double> y = search_values(f, seed, 40);
    const auto hit = std::find_if(y.begin(), y.end(), [&](double v) { return v <= target; });
    total += hit == y.end() ? 41.0 : static_cast<double>(hit - y.begin() + 1);
  }
  return total / 5;
}

double random_minimum(std::uint64_t seed, std::size_t budget) {
  SearchRng rng(seed);
  double m = 1e9;
  for (const auto& p : uniform_random(budget, 2, rng, kNoSnap)) m = std::min(m, bowl(p.point));
  return m;
}

double search_boundary(std::uint64_t seed, std::size_t budget, bool adaptive) {
  SearchRng rng(seed);
  std::vector<Point> x;
  std::vector<bool> pass;
  const auto add = [&](const std::vector<Proposal>& ps) {
    for (const auto& p : ps) {
      x.push_back(p.point);
      pass.push_back(outside_circle(p.point));
    }
  };
  if (!adaptive) {
    add(uniform_random(budget, 2, rng, kNoSnap));
    return misclassified(x, pass, false);
  }
  while (x.size() < budget) {
    const auto next = propose_boundary(2, x, pass, budget - x.size(), 1.0 / 64, kNoSnap);
    if (next.empty()) break;
    add(next);
  }
  return misclassified(x, pass, true);
}

}  // namespace

TEST(SearchGaussianProcess, InterpolatesItsDataAndIsUncertainFarFromIt) {
  std::vector<Point> x;
  std::vector<double> y;
  for (int i = 0; i < 8; ++i) {
    x.push_back({i / 10.0});
    y.push_back(std::sin(6.0 * i / 10.0));
  }
  const GaussianProcess gp = GaussianProcess::fit(x, y);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(gp.predict(x[i]).mean, y[i], 0.05);
  EXPECT_NEAR(gp.predict({0.35}).mean, std::sin(6.0 * 0.35), 0.05);  // between the points
  EXPECT_LT(gp.predict({0.35}).variance, gp.predict({1.0}).variance);  // 0.3 beyond the last point
}

TEST(SearchGaussianProcess, ExpectedImprovementMatchesItsClosedForm) {
  // At mean == best the improvement is sigma * phi(0).
  EXPECT_NEAR(expected_improvement({2.0, 4.0}, 2.0), 2.0 * 0.3989422804, 1e-9);
  // Certain predictions: the plain improvement.
  EXPECT_NEAR(expected_improvement({1.0, 0.0}, 3.0), 2.0, 1e-12);
  EXPECT_NEAR(expected_improvement({4.0, 0.0}, 3.0), 0.0, 1e-12);
  EXPECT_NEAR(normal_cdf(1.96), 0.9750021, 1e-6);
}

TEST(SearchProposal, LatinHypercubeHasOnePointInEverySliceOfEveryDimension) {
  SearchRng rng(7);
  const auto design = latin_hypercube(10, 3, rng, kNoSnap);
  ASSERT_EQ(design.size(), 10u);
  for (std::size_t j = 0; j < 3; ++j) {
    std::vector<int> count(10, 0);
    for (const auto& p : design) ++count[static_cast<std::size_t>(p.point[j] * 10)];
    EXPECT_THAT(count, ::testing::Each(1)) << "dimension " << j;
  }
}

TEST(SearchProposal, GridCoversBothEndsOfEveryDimension) {
  EXPECT_EQ(grid_levels(100, 2), 10u);
  EXPECT_EQ(grid_levels(125, 3), 5u);
  const auto all = grid_points(9, 2, 0, 100);
  ASSERT_EQ(all.size(), 9u);
  EXPECT_EQ(all.front().point, (Point{0.0, 0.0}));
  EXPECT_EQ(all[1].point, (Point{0.0, 0.5}));
  EXPECT_EQ(all.back().point, (Point{1.0, 1.0}));
  EXPECT_EQ(grid_points(9, 2, 7, 5).size(), 2u);  // the rest, from index 7
}

TEST(SearchProposal, IsAPureFunctionOfItsInputsAndSeed) {
  const std::vector<Point> x{{0.1, 0.2}, {0.5, 0.9}, {0.8, 0.4}, {0.3, 0.3}};
  std::vector<double> y;
  for (const auto& p : x) y.push_back(bowl(p));
  SearchRng a(3), b(3), c(4);
  const auto pa = propose_minimum(x, y, 3, a, kNoSnap);
  const auto pb = propose_minimum(x, y, 3, b, kNoSnap);
  const auto pc = propose_minimum(x, y, 3, c, kNoSnap);
  ASSERT_EQ(pa.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(pa[i].point, pb[i].point);
  EXPECT_NE(pa[0].point, pc[0].point);
  // The batch's points differ from each other and from the runs (the believer).
  EXPECT_NE(pa[0].point, pa[1].point);
  EXPECT_EQ(pa[0].why, "expected improvement");
}

TEST(SearchProposal, FindsAKnownMinimumBetterThanRandomSamplingWithTheSameBudget) {
  const double truth = bowl_min();
  double search_error = 0, random_error = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const double s = search_minimum(seed, 30) - truth;
    EXPECT_LT(s, 0.01) << "seed " << seed;  // within 0.01 of the minimum (the range is ~1.4)
    search_error += s;
    random_error += random_minimum(seed, 30) - truth;
  }
  EXPECT_LT(search_error * 5, random_error);
}

// The issue's goal, 5x fewer runs than random sampling, on the shapes criticality takes: the
// goal is the best 3.6 % of the box (the lead brake's tolerance in docs/search.md); random
// sampling needs 27.8 runs on average. A minimum on a face is found by the poll along the
// face from the best corner; one inside the box by expected improvement, with fewer gains.
TEST(SearchProposal, FindsMinimaOnAFaceAnEdgeAndInsideTheBoxInFewRuns) {
  const double random_runs = 1 / 0.036;
  const double face = mean_runs_to_fraction(face_minimum, 0.036);
  const double edge = mean_runs_to_fraction(edge_minimum, 0.036);
  const double inside = mean_runs_to_fraction(bowl, 0.036);
  const double narrow = mean_runs_to_fraction(valley, 0.036);
  std::printf("runs to the best 3.6 %%: face %.1f, edge %.1f, bowl %.1f, valley %.1f; random %.1f\n", face, edge, inside,
              narrow, random_runs);
  EXPECT_LE(face * 5, random_runs);
  EXPECT_LE(edge * 5, random_runs);
  EXPECT_LE(inside * 3, random_runs);
  EXPECT_LE(narrow * 2, random_runs);
}

TEST(SearchProposal, SeedsGiveUnrelatedNumbers) {
  // splitmix64 seeded with seed * its increment made seed 2's numbers seed 1's shifted by one.
  SearchRng one(1), two(2);
  const std::uint64_t first_of_one = one.next();
  const std::uint64_t second_of_one = one.next();
  const std::uint64_t first_of_two = two.next();
  EXPECT_NE(first_of_two, second_of_one);
  EXPECT_NE(first_of_two, first_of_one);
}

TEST(SearchProposal, FindsAKnownBoundaryBetterThanRandomSamplingWithTheSameBudget) {
  // The sparse grid is deterministic: no seed. Random sampling: the mean over eight seeds
  // (1.7 % against 4.9 %; with four seeds of the random source before its seed was mixed,
  // nearly one seed four times, random sampling had looked worse: 6.7 %).
  const double search = search_boundary(0, 100, true);
  double random = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) random += search_boundary(seed, 100, false) / 8;
  std::printf("misclassified after 100 runs: sparse grid %.4f, random %.4f\n", search, random);
  EXPECT_LT(search, 0.02);
  EXPECT_LT(search * 2.5, random);
}

// A straight boundary (fail left of x = 0.3): after the 3 x 3 grid, the two cells it crosses
// are refined by their centres and the midpoints of the edges it crosses only (the vertical
// edges' ends agree: their midpoints are inferred, not run), and the estimate holds.
TEST(SearchProposal, BisectsOnlyTheEdgesTheBoundaryCrosses) {
  const auto passes = [](const Point& p) { return p[0] > 0.3; };
  std::vector<Point> x;
  std::vector<bool> pass;
  const auto grid = propose_boundary(2, x, pass, 1000, 1.0 / 64, kNoSnap);
  ASSERT_EQ(grid.size(), 9u);
  EXPECT_EQ(grid.front().why, "initial grid");
  for (const auto& p : grid) {
    x.push_back(p.point);
    pass.push_back(passes(p.point));
  }
  const auto next = propose_boundary(2, x, pass, 1000, 1.0 / 64, kNoSnap);
  ASSERT_EQ(next.size(), 5u);  // (0.25, y) for y = 0, 0.25, 0.5, 0.75, 1: centres and crossed edges
  for (const auto& p : next) {
    EXPECT_DOUBLE_EQ(p.point[0], 0.25) << p.point[1];
    EXPECT_EQ(p.why, "refine a cell whose corners disagree");
    x.push_back(p.point);
    pass.push_back(passes(p.point));
  }
  // Cells of 1/4 have all their corners (run or inferred): the next level is proposed.
  const auto deeper = propose_boundary(2, x, pass, 1000, 1.0 / 64, kNoSnap);
  ASSERT_FALSE(deeper.empty());
  for (const auto& p : deeper) EXPECT_NEAR(p.point[0], 0.375, 1e-12);
  const BoundaryEstimate b = estimate_boundary(x, pass, 41, kNoSnap);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < b.lattice.size(); ++i)
    if (std::abs(b.lattice[i][0] - 0.3) > 0.13) wrong += b.pass[i] != passes(b.lattice[i]);
  EXPECT_EQ(wrong, 0u);
}

// A large failing block and a small failing island (1.7 % of the box) in a corner, as the
// lead brake's verdict has (docs/search.md): the 3 x 3 grid sees the island at one corner
// only; refining the cells whose corners disagree resolves both, and the estimate ends
// within 1 % of the truth, against random sampling's (Gaussian-process classifier, same runs)
// 2 % or more.
TEST(SearchProposal, ResolvesASmallFailingIslandInACorner) {
  const auto passes = [](const Point& p) {
    const bool block = p[0] > 0.45 + 0.25 * p[1] * p[1] && p[1] < 0.75;
    const bool island = p[0] < 0.13 && p[1] > 0.87;
    return !(block || island);
  };
  std::vector<Point> x;
  std::vector<bool> pass;
  for (int round = 0; round < 500; ++round) {
    const auto next = propose_boundary(2, x, pass, 2, 1.0 / 32, kNoSnap);
    if (next.empty()) break;
    for (const auto& p : next) {
      x.push_back(p.point);
      pass.push_back(passes(p.point));
    }
  }
  const auto wrong = [&](const BoundaryEstimate& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < b.lattice.size(); ++i) n += b.pass[i] != passes(b.lattice[i]);
    return static_cast<double>(n) / static_cast<double>(b.lattice.size());
  };
  const BoundaryEstimate b = estimate_boundary(x, pass, 41, kNoSnap);
  EXPECT_LT(wrong(b), 0.01) << x.size() << " runs";
  EXPECT_FALSE(b.pass[1 * 41 + 39]) << "the island at (0.025, 0.975)";
  double random = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SearchRng rng(seed);
    std::vector<Point> xr;
    std::vector<bool> pr;
    for (const auto& p : uniform_random(x.size(), 2, rng, kNoSnap)) {
      xr.push_back(p.point);
      pr.push_back(passes(p.point));
    }
    random += wrong(estimate_boundary_gp(xr, pr, 41)) / 3;
  }
  std::printf("island: sparse grid %zu runs, misclassified %.4f; random %.4f\n", x.size(), wrong(b), random);
  EXPECT_LT(wrong(b) * 2, random);
}

TEST(SearchProposal, BoundaryRefinementStopsAtTheStatedResolution) {
  std::vector<Point> x;
  std::vector<bool> pass;
  for (int round = 0; round < 100; ++round) {
    const auto next = propose_boundary(2, x, pass, 1000, 1.0 / 8, kNoSnap);
    if (next.empty()) break;
    for (const auto& p : next) {
      x.push_back(p.point);
      pass.push_back(outside_circle(p.point));
    }
  }
  EXPECT_LT(x.size(), 60u);  // finished: cells of 1/8 are not split further
  for (const auto& p : x)
    for (double v : p) EXPECT_DOUBLE_EQ(v * 8, std::round(v * 8));  // on the 1/8 lattice
  EXPECT_LT(misclassified(x, pass, true), 0.06);
}

TEST(SearchProposal, SnapsToWholeNumbersAndAvoidsPointsAlreadyRun) {
  // One dimension of five whole values: proposals land on them and never repeat a run.
  const SnapPoint snap = [](const Point& p) { return Point{std::round(p[0] * 4) / 4}; };
  std::vector<Point> x{{0.0}, {1.0}};
  std::vector<double> y{1.0, 2.0};
  SearchRng rng(1);
  for (const auto& p : propose_minimum(x, y, 3, rng, snap)) {
    EXPECT_DOUBLE_EQ(p.point[0] * 4, std::round(p.point[0] * 4));
    EXPECT_NE(p.point, x[0]);
    EXPECT_NE(p.point, x[1]);
  }
}

namespace {

LogicalScenario logical(const std::string& extra = "") {
  const std::string text = R"({
    "uuid": "L1", "template": "../../scenarios/highway_cut_in.json",
    "parameter_space": {
      "lead": {
        "speed": {"type": "float", "unit": "km/h", "distribution": "uniform", "min": 50, "max": 80},
        "decel": {"type": "float", "distribution": "normal", "mean": 8, "std": 2, "min": 4, "max": 12},
        "lanes": {"type": "int", "distribution": "uniform", "min": 1, "max": 3},
        "gap": {"type": "float", "distribution": "constant", "value": 40.0}
      })" + extra + R"(
    }})";
  return read_logical_scenario(JsonDocument::parse(text, std::string(ORCH_SOURCE_DIR) + "/tests/unit/logical_L1.json"));
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SearchSpace, SearchesNumericRangesAndFixesConstants) {
  const SearchSpace s = logical_search_space(logical(), {});
  EXPECT_EQ(s.keys(), (std::vector<std::string>{"lead.decel", "lead.lanes", "lead.speed"}));
  EXPECT_EQ(s.dims[0].lower, 4);
  EXPECT_EQ(s.dims[0].upper, 12);
  ASSERT_EQ(s.fixed.size(), 1u);
  EXPECT_EQ(s.fixed[0].first, "lead.gap");
  const auto v = s.values({0.5, 0.6, 1.0});
  EXPECT_EQ(v, (std::vector<double>{8.0, 2.0, 80.0}));  // lanes 2.2 rounds to 2
  EXPECT_NEAR(s.snap({0.5, 0.6, 1.0})[1], 0.5, 1e-12);
  const nlohmann::json values = sampled_values_of(s, v, false);
  EXPECT_EQ(values["lead"]["lanes"], 2);
  EXPECT_EQ(values["lead"]["gap"], 40.0);
}

TEST(SearchSpace, SetFixesOrNarrowsParameters) {
  const SearchSpace s = logical_search_space(
      logical(), {parse_space_override("lead.lanes=2"), parse_space_override("lead.speed=60..70")});
  EXPECT_EQ(s.keys(), (std::vector<std::string>{"lead.decel", "lead.speed"}));
  EXPECT_EQ(s.dims[1].lower, 60);
  EXPECT_EQ(s.dims[1].upper, 70);
}

TEST(SearchSpace, BadInputIsNamedWithWhatToDo) {
  EXPECT_THAT(error_of([] { logical_search_space(logical(), {parse_space_override("lead.sped=60")}); }),
              HasSubstr("no parameter \"lead.sped\" (did you mean \"lead.speed\"?)"));
  EXPECT_THAT(error_of([] { logical_search_space(logical(), {parse_space_override("lead.speed=10..70")}); }),
              HasSubstr("outside the parameter's range 50..80"));
  EXPECT_THAT(error_of([] { parse_space_override("lead.speed"); }), HasSubstr("expected KEY=VALUE or KEY=LOW..HIGH"));
  EXPECT_THAT(error_of([] { parse_space_override("lead.speed=9..3"); }), HasSubstr("LOW <= HIGH"));
  const auto with_string = logical(R"(, "env": {"weather": {"type": "string", "distribution": "choice", "choices": ["dry", "wet"]}})");
  EXPECT_THAT(error_of([&] { logical_search_space(with_string, {}); }),
              HasSubstr("parameter \"env.weather\" takes string values: it cannot be searched; fix it with --set env.weather=VALUE"));
  EXPECT_NO_THROW(logical_search_space(with_string, {parse_space_override("env.weather=wet")}));
  EXPECT_THAT(error_of([] {
                logical_search_space(logical(), {parse_space_override("lead.speed=60"), parse_space_override("lead.decel=6"),
                                                 parse_space_override("lead.lanes=1")});
              }),
              HasSubstr("no parameter is left to search"));
}

TEST(SearchObjective, ReadsMetricsCriteriaAndVerdicts) {
  const nlohmann::json result = nlohmann::json::parse(R"({
    "verdict": "failure", "sim_time": 12.5, "collision": null,
    "actors": [{"actor_id": 0, "ego": true}, {"actor_id": 1, "ego": false}],
    "metrics": {"Ego": {"min_ttc": {"value": 1.5, "time": 3}, "min_gap": null, "standstill_time": 2.0},
                "Lead": {"max_decel": {"value": 6.0, "time": 5}}},
    "criteria": [{"name": "keep_ttc", "actual": 1.5, "success": false}]})");
  EXPECT_EQ(objective_value(result, "min_ttc"), 1.5);
  EXPECT_EQ(objective_value(result, "Lead.max_decel"), 6.0);
  EXPECT_EQ(objective_value(result, "standstill_time"), 2.0);
  EXPECT_EQ(objective_value(result, "min_gap"), std::nullopt);
  EXPECT_EQ(objective_value(result, "sim_time"), 12.5);
  EXPECT_EQ(objective_value(result, "criterion:keep_ttc"), 1.5);
  EXPECT_FALSE(criterion_passed(result, "verdict"));
  EXPECT_TRUE(criterion_passed(result, "collision"));
  EXPECT_FALSE(criterion_passed(result, "keep_ttc"));
  EXPECT_THAT(error_of([&] { criterion_passed(result, "keep_tc"); }), HasSubstr("did you mean \"keep_ttc\""));
  EXPECT_THAT(error_of([&] { objective_value(result, "Leed.max_decel"); }), HasSubstr("did you mean \"Lead\""));
  EXPECT_THAT(error_of([] { check_objective("min_tcc"); }), HasSubstr("no metric \"min_tcc\" (did you mean \"min_ttc\"?)"));
  EXPECT_NO_THROW(check_objective("Ego.max_decel"));
}
