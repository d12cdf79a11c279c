// The plan view's cached evaluation and the indexes behind projections, against references
// computed independently: spirals and cubic polynomials against a fine Simpson integration
// in long double, the table's evaluation against the direct one at the boundaries of its
// pieces and records, s -> pose -> s round trips through the projection, the point tree
// against a walk over every point, and to_road against projecting onto every road.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "opendrive/point_tree.hpp"
#include "opendrive/road_grid.hpp"
#include "opendrive/road_network.hpp"
#include "opendrive/xodr_reader.hpp"

namespace orch::opendrive {
namespace {

// Independent reference: composite Simpson over n intervals in long double of (cos, sin)
// of the heading h0 + k0 s + (k1 - k0) s^2 / (2 L) from 0 to ds.
Pose2 spiral_reference(const Pose2& start, double k0, double k1, double length, double ds, int n = 20000) {
  const long double rate = (static_cast<long double>(k1) - k0) / length;
  const auto heading = [&](long double s) { return start.heading + k0 * s + 0.5L * rate * s * s; };
  const long double h = static_cast<long double>(ds) / n;
  long double x = 0, y = 0;
  for (int i = 0; i <= n; ++i) {
    const long double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    x += w * std::cos(heading(i * h));
    y += w * std::sin(heading(i * h));
  }
  return {static_cast<double>(start.x + x * h / 3), static_cast<double>(start.y + y * h / 3),
          static_cast<double>(heading(ds))};
}

struct SpiralCase {
  double k0, k1, length;
};

TEST(OpenDrivePlanViewCache, SpiralPosesMatchAFineSimpsonIntegration) {
  // A gentle motorway transition, a tight junction spiral (1 rad in 2 m at its end), and a
  // long one that reverses its curvature; at knots, between them, at both ends.
  for (const SpiralCase c : {SpiralCase{0.0, 0.004, 100.0}, SpiralCase{-0.05, 0.5, 30.0},
                             SpiralCase{0.01, -0.012, 777.7}}) {
    const Pose2 start{12.0, -7.0, 0.4};
    const PlanView view({Geometry{5.0, start, c.length, Spiral{c.k0, c.k1}}});
    for (const double ds : {0.0, 0.3, 1.999, 2.0, 2.001, 13.37, c.length / 2, c.length - 0.01, c.length}) {
      const Pose2 want = spiral_reference(start, c.k0, c.k1, c.length, ds);
      const Pose2 got = view.pose(5.0 + ds);
      EXPECT_NEAR(got.x, want.x, 1e-9) << c.k0 << " " << c.k1 << " ds=" << ds;
      EXPECT_NEAR(got.y, want.y, 1e-9) << c.k0 << " " << c.k1 << " ds=" << ds;
      EXPECT_NEAR(got.heading, want.heading, 1e-12);
      // The table and the direct integration from the record's start agree to rounding.
      const Pose2 direct = evaluate(view.geometries().front(), ds);
      EXPECT_NEAR(got.x, direct.x, 1e-10);
      EXPECT_NEAR(got.y, direct.y, 1e-10);
    }
  }
}

TEST(OpenDrivePlanViewCache, Poly3PosesMatchTheDirectEvaluationAndLieOnTheCurve) {
  const Poly3 poly{0.5, 0.1, 0.004, -0.00002};
  const PlanView view({Geometry{0.0, {1.0, 2.0, 0.3}, 80.0, poly}});
  for (const double ds : {0.0, 1.0, 2.0, 33.3, 79.99, 80.0}) {
    const Pose2 cached = view.pose(ds);
    const Pose2 direct = evaluate(view.geometries().front(), ds);
    EXPECT_NEAR(cached.x, direct.x, 1e-10) << ds;
    EXPECT_NEAR(cached.y, direct.y, 1e-10) << ds;
    EXPECT_NEAR(cached.heading, direct.heading, 1e-12) << ds;
    EXPECT_NEAR(view.curvature(ds), curvature(view.geometries().front(), ds), 1e-12);
  }
  // Independently: the point at ds = 40 lies at arc length 40 along v(u) (Simpson in u).
  const Pose2 p = view.pose(40.0);
  const double c = std::cos(0.3), s = std::sin(0.3);
  const double u = c * (p.x - 1.0) + s * (p.y - 2.0);
  const double v = -s * (p.x - 1.0) + c * (p.y - 2.0);
  EXPECT_NEAR(v, poly.a + u * (poly.b + u * (poly.c + u * poly.d)), 1e-9);
  const int n = 100000;
  long double arc = 0;
  for (int i = 0; i <= n; ++i) {
    const long double x = static_cast<long double>(u) * i / n;
    const long double dv = poly.b + 2 * poly.c * x + 3 * poly.d * x * x;
    arc += ((i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2)) * std::sqrt(1 + dv * dv);
  }
  EXPECT_NEAR(static_cast<double>(arc * u / n / 3), 40.0, 1e-9);
}

// A fixed, sized set of random records of every kind (seeded: the same 200 records every
// run), each evaluated through the plan view (binary search, table, one quadrature piece)
// and by the direct integration from the record's start, at 50 random s and at its ends.
TEST(OpenDrivePlanViewCache, RandomRecordsMatchTheDirectIntegrationEverywhere) {
  std::mt19937 rng(20261126);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  for (int n = 0; n < 200; ++n) {
    const double length = between(0.5, 1500.0);
    Shape shape;
    switch (n % 5) {
      case 0: shape = Line{}; break;
      case 1: shape = Arc{between(-0.2, 0.2)}; break;
      case 2: shape = Spiral{between(-0.05, 0.05), between(-0.05, 0.05)}; break;
      case 3: shape = Poly3{between(-2, 2), between(-0.3, 0.3), between(-1e-3, 1e-3), between(-1e-6, 1e-6)}; break;
      default:
        shape = ParamPoly3{0, length, between(-5, 5), between(-5, 5), 0, 0, between(-20, 20), between(-20, 20), true};
    }
    // Three records: the random one between two lines, so the search by s is exercised too.
    std::vector<Geometry> g;
    g.push_back(Geometry{0.0, {between(-1e4, 1e4), between(-1e4, 1e4), between(-M_PI, M_PI)}, 10.0, Line{}});
    g.push_back(Geometry{10.0, evaluate(g[0], 10.0), length, shape});
    g.push_back(Geometry{10.0 + length, evaluate(g[1], length), 10.0, Line{}});
    const PlanView view(g);
    std::vector<double> at{0.0, 1e-12, length / 2, length - 1e-9, length};
    for (int i = 0; i < 50; ++i) at.push_back(between(0.0, length));
    for (const double ds : at) {
      const Pose2 direct = evaluate(g[1], ds);
      const double s = 10.0 + ds;
      const Pose2 got = view.pose(s);
      // At the record's end the next record (a line from the direct end pose) answers.
      EXPECT_NEAR(got.x, direct.x, 1e-9) << "record " << n << " ds=" << ds;
      EXPECT_NEAR(got.y, direct.y, 1e-9) << "record " << n << " ds=" << ds;
      if (ds < length) {
        EXPECT_NEAR(got.heading, direct.heading, 1e-12) << "record " << n << " ds=" << ds;
        EXPECT_NEAR(view.curvature(s), curvature(g[1], ds), 1e-12) << "record " << n << " ds=" << ds;
      }
    }
  }
}

TEST(OpenDrivePlanViewCache, ProfileRecordSearchIsTheLastRecordStartingAtOrBeforeS) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> start(0.0, 500.0);
  for (int n = 0; n < 50; ++n) {
    std::vector<CubicRecord> records(static_cast<std::size_t>(n));
    for (CubicRecord& r : records) r.s = std::round(start(rng));  // repeated starts too
    std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.s < b.s; });
    for (int q = 0; q < 200; ++q) {
      const double s = q % 4 == 0 && n > 0 ? records[static_cast<std::size_t>(q) % records.size()].s : start(rng) - 10;
      const CubicRecord* want = nullptr;  // the walk the search replaced
      for (const CubicRecord& r : records) {
        if (r.s <= s + 1e-9) want = &r;
        else break;
      }
      EXPECT_EQ(record_at(records, s), want) << n << " records, s=" << s;
    }
  }
}

// line 100 m, spiral 0 -> 0.02 over 50 m, arc 0.02 for 60 m, spiral back to 0 over 50 m,
// line 100 m: each record starts where the direct evaluation of the previous one ends.
PlanView transition_road() {
  std::vector<Geometry> g;
  const auto add = [&](double length, Shape shape) {
    Pose2 start{};
    double s = 0;
    if (!g.empty()) {
      start = evaluate(g.back(), g.back().length);
      s = g.back().s + g.back().length;
    }
    g.push_back(Geometry{s, start, length, shape});
  };
  add(100, Line{});
  add(50, Spiral{0.0, 0.02});
  add(60, Arc{0.02});
  add(50, Spiral{0.02, 0.0});
  add(100, Line{});
  return PlanView(g);
}

TEST(OpenDrivePlanViewCache, PosesAreContinuousAcrossRecordBoundaries) {
  const PlanView view = transition_road();
  const auto& g = view.geometries();
  for (std::size_t i = 1; i < g.size(); ++i) {
    const double b = g[i].s;
    const Pose2 before = view.pose(std::nextafter(b, 0.0));
    const Pose2 at = view.pose(b);
    EXPECT_NEAR(before.x, at.x, 1e-9) << "record " << i;
    EXPECT_NEAR(before.y, at.y, 1e-9) << "record " << i;
    EXPECT_NEAR(before.heading, at.heading, 1e-9) << "record " << i;
    EXPECT_NEAR(view.curvature(b - 1e-7), view.curvature(b), 1e-8) << "record " << i;
  }
}

TEST(OpenDrivePlanViewCache, ProjectionRoundTripsEverySOnACurvedRoad) {
  std::vector<Road> roads(1);
  roads[0].id = "r";
  roads[0].plan_view = transition_road();
  roads[0].length = roads[0].plan_view.length();
  std::mt19937 rng(20261126);  // fixed seed: the same 400 points every run
  std::uniform_real_distribution<double> along(0.0, roads[0].length);
  std::uniform_real_distribution<double> across(-12.0, 12.0);  // well inside the 50 m radius
  for (int i = 0; i < 400; ++i) {
    const double s = along(rng);
    const double t = across(rng);
    const Pose2 p = roads[0].world(s, t);
    const RoadCoordinate back = project(roads[0], p.x, p.y);
    EXPECT_NEAR(back.s, s, 1e-8) << s << " " << t;
    EXPECT_NEAR(back.t, t, 1e-8) << s << " " << t;
  }
}

TEST(OpenDrivePlanViewCache, PointTreeFindsWhatAWalkOverEveryPointFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  for (const std::size_t n : {1u, 7u, 8u, 9u, 100u, 1000u}) {
    std::vector<double> xs, ys;
    for (std::size_t i = 0; i < n; ++i) {
      // Every third point repeats an earlier one: ties go to the lowest index.
      if (i % 3 == 2) xs.push_back(xs[i / 2]), ys.push_back(ys[i / 2]);
      else xs.push_back(std::round(coordinate(rng))), ys.push_back(std::round(coordinate(rng)));
    }
    const PointTree tree(xs, ys);
    for (int q = 0; q < 300; ++q) {
      const double x = std::round(coordinate(rng) * 1.5), y = std::round(coordinate(rng) * 1.5);
      std::size_t want = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < n; ++i) {
        const double d2 = (x - xs[i]) * (x - xs[i]) + (y - ys[i]) * (y - ys[i]);
        if (d2 < best) best = d2, want = i;
      }
      EXPECT_EQ(tree.nearest(x, y), want) << "n=" << n << " at " << x << "," << y;
    }
  }
  EXPECT_EQ(PointTree().nearest(1.0, 2.0), 0u);
  EXPECT_EQ(PointTree({1.0, 2.0}, {0.0, 0.0}).nearest(std::nan(""), 0.0), 0u);
}

// Three roads: a straight one, an S-curve crossing it, and a short one parallel to the
// first and overlapping its left lanes (to_road must keep choosing the same road there).
const char* kCrossingRoads = R"(<?xml version="1.0"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6"/>
  <road id="a" length="300" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="300"><line/></geometry></planView>
    <lanes><laneSection s="0">
      <left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
            <lane id="2" type="sidewalk"><width sOffset="0" a="2" b="0.01" c="0" d="0"/></lane></left>
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>
  <road id="b" length="200" junction="-1">
    <planView>
      <geometry s="0" x="100" y="-80" hdg="1.2" length="60"><spiral curvStart="0" curvEnd="0.02"/></geometry>
      <geometry s="60" x="117.57" y="-23.17" hdg="1.8" length="140"><spiral curvStart="0.02" curvEnd="-0.02"/></geometry>
    </planView>
    <lanes><laneOffset s="0" a="0.2" b="0" c="0" d="0"/><laneSection s="0">
      <left><lane id="1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></left>
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>
  <road id="c" length="80" junction="-1">
    <planView><geometry s="0" x="150" y="4" hdg="0" length="80"><line/></geometry></planView>
    <lanes><laneSection s="0">
      <left><lane id="1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></left>
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>
</OpenDRIVE>)";

// to_road as it was before the grid: every road projected, the same preference.
std::optional<RoadCoordinate> to_road_over_every_road(const RoadNetwork& net, double x, double y) {
  std::optional<RoadCoordinate> best;
  bool best_on_lane = false;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const Road& r : net.roads()) {
    const RoadCoordinate c = project(r, x, y);
    const Pose2 ref = r.world(c.s, c.t);
    const double distance = std::hypot(ref.x - x, ref.y - y) + std::abs(c.t) * 1e-9;
    const bool on_lane = r.lane_at(c.s, c.t).has_value() && distance < 1e-3;
    if ((on_lane && !best_on_lane) || (on_lane == best_on_lane && distance < best_distance)) {
      best = c;
      best_on_lane = on_lane;
      best_distance = distance;
    }
  }
  return best;
}

TEST(OpenDrivePlanViewCache, ToRoadOverTheGridChoosesWhatEveryRoadWouldGive) {
  const RoadNetwork net = read_xodr_text(kCrossingRoads, "crossing.xodr");
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-20.0, 320.0), y(-100.0, 140.0);
  int on_a_lane = 0;
  for (int i = 0; i < 3000; ++i) {
    const double px = x(rng), py = y(rng);
    const auto got = net.to_road(px, py);
    const auto want = to_road_over_every_road(net, px, py);
    ASSERT_EQ(got.has_value(), want.has_value());
    EXPECT_EQ(got->road_id, want->road_id) << px << "," << py;
    EXPECT_EQ(got->s, want->s) << px << "," << py;
    EXPECT_EQ(got->t, want->t) << px << "," << py;
    if (net.road(got->road_id).lane_at(got->s, got->t)) ++on_a_lane;
  }
  EXPECT_GT(on_a_lane, 100);  // the sample holds both cases: on a lane and off every lane
  EXPECT_LT(on_a_lane, 2900);
}

TEST(OpenDrivePlanViewCache, LateralReachBoundsEveryLaneBorder) {
  const RoadNetwork net = read_xodr_text(kCrossingRoads, "crossing.xodr");
  // a: 3.5 + (2 + 0.01 * 300) on the left; b: offset 0.2 + 3.
  EXPECT_NEAR(lateral_reach(net.road("a")), 8.5, 1e-12);
  EXPECT_NEAR(lateral_reach(net.road("b")), 3.2, 1e-12);
  // A width that bulges between its ends: 2 + 0.3 s - 0.003 s^2 peaks at s = 50 (9.5 m).
  Road r = net.road("c");
  r.sections.front().left.front().widths = {CubicRecord{0.0, 2.0, 0.3, -0.003, 0.0}};
  EXPECT_NEAR(lateral_reach(r), 9.5, 1e-12);
}

}  // namespace
}  // namespace orch::opendrive
