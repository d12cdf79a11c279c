// Fix I of the map builder (docs/generated-maps-history.md): a route starting inside a
// junction that its own later lap passes, a route starting just past the end of a lane off
// every path from it, and the junction shape that goes round a lane bent back in a U. Without
// SUMO: the plan `map build` hands to netconvert, and the shape it gives a junction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "map/junction_shape.hpp"
#include "map/net_plan.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;

namespace {

// Points 1 m apart along `corners`, each inner corner rounded with an arc of `radius`.
std::vector<Vec2> rounded(const std::vector<Vec2>& corners, double radius) {
  std::vector<Vec2> pts;
  Vec2 from = corners.front();
  const auto line = [&](const Vec2& a, const Vec2& b) {
    const double len = (b - a).norm();
    for (double s = 0; s < len - 1e-9; s += 1.0) pts.push_back(a + (b - a) * (s / len));
  };
  for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
    const Vec2 d1 = (corners[i] - corners[i - 1]).normalized();
    const Vec2 d2 = (corners[i + 1] - corners[i]).normalized();
    const Vec2 t1 = corners[i] - d1 * radius;  // right angles only: the arc's ends
    const Vec2 t2 = corners[i] + d2 * radius;
    line(from, t1);
    const Vec2 centre = t1 + d2 * radius;
    const double a0 = std::atan2(t1.y() - centre.y(), t1.x() - centre.x());
    const double turn = std::atan2(d1.x() * d2.y() - d1.y() * d2.x(), d1.dot(d2));
    const int n = static_cast<int>(std::ceil(radius * std::abs(turn)));
    for (int k = 0; k < n; ++k) {
      const double a = a0 + turn * k / n;
      pts.emplace_back(centre.x() + radius * std::cos(a), centre.y() + radius * std::sin(a));
    }
    from = t2;
  }
  line(from, corners.back());
  pts.push_back(corners.back());
  return pts;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

TEST(JunctionRouteEnds, ARouteStartingInsideAJunctionItsLaterLapPassesGetsALaneOfItsOwnThere) {
  // Seed 734: a route starts 1 m west of a street and crosses it, drives round a block and
  // comes back north along that street through its own start. Its first metres lie in the
  // junction where the later lap crosses them. Continued through that junction (as a route
  // starting inside one alone on its lane is), its first lane would start before the junction,
  // cross it and end at it after the loop: netconvert cuts a lane where its own junction's
  // shape crosses it, and kept 21 m of 1 km. The route starts on a dead-end lane of its own.
  const std::vector<Vec2> loop = rounded({{-1, 0}, {60, 0}, {60, -60}, {0, -60}, {0, 60}}, 10.0);
  const std::vector<test::SyntheticRoute> routes = {{"round", loop}};
  test::TempDir dir("route_ends_lap");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "lap", routes).string());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  EXPECT_EQ(plan.junctions, 1);
  bool own_start = false;
  for (const PlannedEdge& e : plan.edges) {
    own_start = own_start || starts_with(e.id, "round.start");
    // No lane both passes through the junction and ends (starts) at it.
    EXPECT_FALSE(e.from == e.to) << e.id;
    for (const PlannedNode& n : plan.nodes) {
      if (n.type.empty() || (e.from != n.id && e.to != n.id)) continue;
      for (const PlannedLane& l : e.lanes) {
        const double at_node = e.to == n.id ? l.shape.length() : 0.0;
        const Polyline::Projection pr = l.shape.project(n.position);
        EXPECT_TRUE(pr.distance > 1.0 || std::abs(pr.s - at_node) < 10.0)
            << e.id << " passes junction " << n.id << " " << pr.s << " m along, far from its end there";
      }
    }
  }
  EXPECT_TRUE(own_start);
}

TEST(JunctionRouteEnds, ARouteStartingPastALaneEndOffEveryPathFromItGetsALaneOfItsOwn) {
  // Seed 615: a route starts 1.5 m into a junction, along the lane after it, 0.16-0.25 m
  // beside the turn of a route coming from the lane before. Taken to come from that lane (it
  // starts within 3 m past its end, straight along it), it drove the other route's connection
  // 0.16 m off; off every path between the two lanes, it gets a dead-end lane of its own.
  const double radius = 25.0;  // the turn from y = 0 south onto x = 0, about (-25, -25)
  const std::vector<Vec2> turn = rounded({{-80, 0}, {0, 0}, {0, -80}}, radius);
  // From where the turn lies 0.25 m west of x = 0 (its tangent 8 degrees off south).
  const double y0 = -radius + radius * std::sqrt(1 - std::pow(1 - 0.25 / radius, 2));
  std::vector<Vec2> after;
  for (double y = y0; y >= -80 + 1e-9; y -= 1.0) after.emplace_back(0.0, y);
  const std::vector<test::SyntheticRoute> routes = {{"turn", turn}, {"after", after}};
  test::TempDir dir("route_ends_past");
  const WaypointFile wf = load_waypoint_file(test::write_waypoint_file(dir.path(), "past", routes).string());
  const NetPlan plan = plan_net(wf, NetPlanSettings{});
  bool own_start = false;
  for (const PlannedEdge& e : plan.edges) own_start = own_start || starts_with(e.id, "after.start");
  EXPECT_TRUE(own_start);
  for (const std::string& note : plan.notes) EXPECT_EQ(note.find("along different paths"), std::string::npos) << note;
}

TEST(JunctionRouteEnds, TheJunctionTreeGoesRoundALaneBentBackInAU) {
  // Seed 831: a lane turning away from its road mid-block in a U ends 23.5 m from its
  // neighbour's end at the same node; the line between the ends crosses the U, and no way
  // round it lies within 6 m of the lane ends. The tree's grid reaches farther out there.
  std::vector<Vec2> straight;
  for (double y = 30; y >= 0; y -= 1.0) straight.emplace_back(0, y);
  const std::vector<Vec2> bent = rounded({{-3.5, 30}, {-3.5, -25}, {-23.5, -25}, {-23.5, 0}}, 10.0);
  const Polyline straight_lane(straight);
  const Polyline bent_lane(bent);
  const std::vector<LaneEnd> ends{{&straight_lane, true}, {&bent_lane, true}};
  const Vec2 middle = 0.5 * (straight.back() + bent.back());
  const std::vector<TreeNode> nodes{{straight.back(), {}}, {bent.back(), {}}, {middle, {}}};
  EXPECT_GT(cut_length({straight.back(), bent.back()}, ends), 0.0);  // the line across cuts the U
  const std::vector<Vec2> tree = uncut_tree(nodes, ends);
  ASSERT_FALSE(tree.empty());
  EXPECT_EQ(cut_length(tree, ends), 0.0);
  for (const Vec2& end : {straight.back(), bent.back()})
    EXPECT_TRUE(std::any_of(tree.begin(), tree.end(), [&](const Vec2& p) { return (p - end).norm() < 1e-9; }));
}
