// LaneMap on the shipped nets and on a split synthetic road: waypoints resolve to the right
// lanes in SUMO's lane coordinates, and the per-step queries agree with exact placement.
#include <algorithm>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "integration/map_fixtures.hpp"

using namespace orch;
using orch::test::road_points;
using orch::test::RoadShape;
using orch::test::TempDir;

namespace {

struct ShippedMap {
  MapManifest manifest;
  WaypointFile waypoints;
  LaneMap lanes;
};

// Loaded once per test binary: the ALKS road has 30,000 waypoints.
const ShippedMap& shipped(const std::string& id) {
  static std::map<std::string, ShippedMap> cache;
  auto it = cache.find(id);
  if (it == cache.end()) {
    MapManifest m = load_map_manifest(test::shipped_map_dir(id));
    WaypointFile w = load_waypoint_file(m.waypoint_path().string());
    LaneMap l = LaneMap::build(m.net_path().string(), w);
    it = cache.emplace(id, ShippedMap{std::move(m), std::move(w), std::move(l)}).first;
  }
  return it->second;
}

// The lanes a route runs on, in driving order: the shipped roads are cut into edges of at
// most max_edge_length_m, so a route has one lane per piece.
std::vector<const LaneInfo*> lanes_of_route(const ShippedMap& m, const std::string& route) {
  std::vector<const LaneInfo*> out;
  const RouteLanes* rl = m.lanes.route(route);
  EXPECT_NE(rl, nullptr) << route;
  if (rl == nullptr) return out;
  for (const auto& id : rl->lanes) out.push_back(&m.lanes.lane(id));
  return out;
}

int lanes_on_edge(const LaneMap& lanes, const std::string& edge) {
  int n = 0;
  for (const auto& l : lanes.lanes()) n += l.edge == edge ? 1 : 0;
  return n;
}

}  // namespace

TEST(LaneMap, EveryShippedWaypointLiesOnItsLaneCentre) {
  for (const char* id : {"highway", "ALKS_Road", "ALKS_Road_Different_Curvatures"}) {
    const ShippedMap& m = shipped(id);
    EXPECT_LE(test::max_waypoint_distance(m.lanes, m.waypoints), 0.10) << id;
    for (const auto& r : m.waypoints.routes) {
      const RouteLanes* rl = m.lanes.route(r.id);
      ASSERT_NE(rl, nullptr);
      ASSERT_EQ(rl->points.size(), r.points.size());
      // SUMO position -> shape offset through the geometry factor lands on the waypoint.
      for (std::size_t i = 0; i < r.points.size(); i += 97) {
        const LanePlace& p = rl->points[i];
        const LaneInfo& lane = m.lanes.lane(p.lane);
        const Vec2 on_lane = lane.shape.offset_point(p.lane_pos * lane.geometry_factor(), p.lateral);
        EXPECT_LT((on_lane - r.line.point(i)).norm(), 0.01) << id << " " << r.id << " wp " << i;
      }
    }
  }
}

TEST(LaneMap, AlksLanesAreOrderedRightToLeft) {
  for (const char* id : {"ALKS_Road", "ALKS_Road_Different_Curvatures"}) {
    const ShippedMap& m = shipped(id);
    const auto w1 = lanes_of_route(m, "Waypoint01");  // leftmost, y = -4.5
    const auto w2 = lanes_of_route(m, "Waypoint02");
    const auto w3 = lanes_of_route(m, "Waypoint03");  // rightmost, y = -11.5
    ASSERT_GT(w1.size(), 1u) << id << ": a 10 km road is cut into pieces";
    ASSERT_EQ(w1.size(), w2.size()) << id;
    ASSERT_EQ(w1.size(), w3.size()) << id;
    for (std::size_t i = 0; i < w1.size(); ++i) {
      EXPECT_EQ(w3[i]->index, 0) << id << " piece " << i;
      EXPECT_EQ(w2[i]->index, 1) << id << " piece " << i;
      EXPECT_EQ(w1[i]->index, 2) << id << " piece " << i;
      EXPECT_EQ(w1[i]->edge, w3[i]->edge) << id << " piece " << i;
      EXPECT_NEAR(w2[i]->width, 3.5, 0.01);
      EXPECT_NEAR(w2[i]->speed, 80 / 3.6, 1e-3);
      // No piece is longer than the manifest's max_edge_length_m (250 m).
      EXPECT_LE(w2[i]->length * w2[i]->geometry_factor(), 250.0 + 1e-6) << id << " piece " << i;
    }
  }
}

TEST(LaneMap, HighwayHasOneEdgePerDirectionWithWaypoint01Leftmost) {
  const ShippedMap& m = shipped("highway");
  const auto w1 = lanes_of_route(m, "Waypoint01");  // x = -36 at the start, driving +y
  const auto w3 = lanes_of_route(m, "Waypoint03");
  const auto w1r = lanes_of_route(m, "Waypoint01R");  // x = -9 at the end, driving -y
  const auto w3r = lanes_of_route(m, "Waypoint03R");
  ASSERT_EQ(w1.size(), w3.size());
  ASSERT_EQ(w1r.size(), w3r.size());
  for (std::size_t i = 0; i < w1.size(); ++i) {
    EXPECT_EQ(w1[i]->edge, w3[i]->edge);
    EXPECT_EQ(w1[i]->index, lanes_on_edge(m.lanes, w1[i]->edge) - 1);
    EXPECT_EQ(w3[i]->index, 0);
    EXPECT_NEAR(w1[i]->width, 4.0, 0.01);
    EXPECT_NEAR(w1[i]->speed, 100 / 3.6, 1e-3);
    for (const auto* r : w1r) EXPECT_NE(w1[i]->edge, r->edge) << "opposite directions share no edge";
  }
  for (std::size_t i = 0; i < w1r.size(); ++i) {
    EXPECT_EQ(w1r[i]->index, lanes_on_edge(m.lanes, w1r[i]->edge) - 1);
    EXPECT_EQ(w3r[i]->index, 0);
  }
}

TEST(LaneMap, LanePositionsIncreaseAlongEveryRoute) {
  for (const char* id : {"highway", "ALKS_Road_Different_Curvatures"}) {
    const ShippedMap& m = shipped(id);
    for (const auto& r : m.waypoints.routes) {
      const RouteLanes& rl = *m.lanes.route(r.id);
      const auto& pts = rl.points;
      // The first waypoint lies lane_extension (20 m) into the lane.
      EXPECT_NEAR(pts.front().lane_pos * m.lanes.lane(pts.front().lane).geometry_factor(), 20.0, 0.05);
      std::size_t lane_at = 0;  // index into rl.lanes of the current waypoint's lane
      for (std::size_t i = 1; i < pts.size(); ++i) {
        if (pts[i].lane == pts[i - 1].lane) {
          ASSERT_GT(pts[i].lane_pos, pts[i - 1].lane_pos) << id << " " << r.id << " wp " << i;
          continue;
        }
        // A new piece: it is a later lane of the route, and positions restart near 0.
        const auto next = std::find(rl.lanes.begin() + static_cast<std::ptrdiff_t>(lane_at), rl.lanes.end(), pts[i].lane);
        ASSERT_NE(next, rl.lanes.end()) << id << " " << r.id << " wp " << i;
        const auto at = static_cast<std::size_t>(next - rl.lanes.begin());
        ASSERT_GT(at, lane_at) << id << " " << r.id << " wp " << i;
        lane_at = at;
        EXPECT_LT(pts[i].lane_pos, 30.0) << id << " " << r.id << " wp " << i;
      }
      EXPECT_EQ(lane_at + 1, rl.lanes.size()) << id << " " << r.id << ": the last waypoint lies on the last lane";
    }
  }
}

TEST(LaneMap, PlaceOnRouteInterpolatesLikeExactPlacement) {
  const ShippedMap& m = shipped("ALKS_Road_Different_Curvatures");
  const WaypointRoute& r = *m.waypoints.find("Waypoint03");
  for (const double s : {0.0, 10.3, 1234.56, 2500.0, r.line.length() - 0.4}) {
    for (const double lateral : {0.0, 1.2, -3.5}) {
      const LanePlace fast = m.lanes.place_on_route(r, s, lateral);
      const LanePlace exact = m.lanes.place_on_lane(fast.lane, r.line.offset_point(s, lateral));
      // Offsets sideways follow the route's normal, exact placement the simplified lane's
      // chords: they part by about |lateral| times the angle between them (< 0.01 rad).
      const double tolerance = 0.02 + 0.01 * std::abs(lateral);
      EXPECT_NEAR(fast.lane_pos, exact.lane_pos, tolerance) << s << " " << lateral;
      EXPECT_NEAR(fast.lateral, exact.lateral, tolerance) << s << " " << lateral;
    }
  }
  // Beyond the last waypoint the lane goes on (lane_extension); the place follows it.
  const LanePlace end = m.lanes.place_on_route(r, r.line.length(), 0);
  const LanePlace past = m.lanes.place_on_route(r, r.line.length() + 10, 0);
  EXPECT_EQ(past.lane, end.lane);
  EXPECT_NEAR(past.lane_pos - end.lane_pos, 10 / m.lanes.lane(end.lane).geometry_factor(), 0.05);
  EXPECT_NEAR(past.lateral, 0, 0.05);
}

TEST(LaneMap, LocateRespectsTheDirectionOfTravel) {
  const ShippedMap& m = shipped("highway");
  const WaypointRoute& r = *m.waypoints.find("Waypoint02");
  const double s = 700;
  const Vec2 p = r.line.point_at(s);
  const double heading = r.line.heading_at(s);
  const auto same = m.lanes.locate(p, heading);
  ASSERT_TRUE(same.has_value());
  EXPECT_EQ(m.lanes.lane(same->lane).routes, std::vector<std::string>{"Waypoint02"});
  EXPECT_LT(same->distance, 0.05);
  // Facing the other way, the nearest lane in that direction is ~15 m away (the other
  // carriageway), beyond the default 10 m search radius.
  EXPECT_FALSE(m.lanes.locate(p, heading + std::numbers::pi).has_value());
  const auto other = m.lanes.locate(p, heading + std::numbers::pi, 30.0);
  ASSERT_TRUE(other.has_value());
  EXPECT_EQ(m.lanes.lane(other->lane).routes, std::vector<std::string>{"Waypoint03R"});
}

TEST(LaneMap, RouteEdgesFollowTheDrivingOrder) {
  TempDir dir("lanemap");
  RoadShape road;
  road.straight = 200;
  road.radius = 400;
  road.arc_length = 500;
  // R1 and R2 run the whole road; R3 exists only in the middle: three edges.
  const auto m = test::build_synthetic(dir, "split", {{"R1", road_points(road, 0, 0, 700)},
                                                       {"R2", road_points(road, 3.5, 0, 700)},
                                                       {"R3", road_points(road, 7.0, 250, 450)}});
  const WaypointFile& w = m.waypoints;
  const LaneMap lanes = m.lanes();
  EXPECT_LE(test::max_waypoint_distance(lanes, w), 0.10);
  const WaypointRoute& r1 = *w.find("R1");
  EXPECT_EQ(lanes.route_edges(r1, 0, r1.line.length()),
            (std::vector<std::string>{"R1+R2+R3#0", "R1+R2+R3#1", "R1+R2+R3#2"}));
  EXPECT_EQ(lanes.route_edges(r1, 300, r1.line.length()), (std::vector<std::string>{"R1+R2+R3#1", "R1+R2+R3#2"}));
  EXPECT_EQ(lanes.route_edges(r1, 10, 20), (std::vector<std::string>{"R1+R2+R3#0"}));
  EXPECT_EQ(lanes.route_edges(*w.find("R3"), 0, 200), (std::vector<std::string>{"R1+R2+R3#1"}));
  // Lane positions restart on each edge and the waypoint places follow the edges in order.
  const auto& pts = lanes.route("R1")->points;
  std::vector<std::string> edges_seen;
  for (const auto& p : pts)
    if (edges_seen.empty() || edges_seen.back() != lanes.lane(p.lane).edge) edges_seen.push_back(lanes.lane(p.lane).edge);
  EXPECT_EQ(edges_seen, lanes.route_edges(r1, 0, r1.line.length()));
  // Across an edge boundary, place_on_route still lands within the lane.
  for (double s = 225; s < 235; s += 0.25) EXPECT_LT(lanes.place_on_route(r1, s, 0).distance, 0.05) << s;
}

TEST(LaneMap, RefusesANetBuiltFromOtherWaypoints) {
  const ShippedMap& alks = shipped("ALKS_Road");
  const ShippedMap& highway = shipped("highway");
  EXPECT_THROW(LaneMap::build(alks.manifest.net_path().string(), highway.waypoints), MapError);
  EXPECT_THROW(LaneMap::build("/nonexistent/net.xml", highway.waypoints), MapError);
  EXPECT_THROW((void)alks.lanes.place_on_route(*highway.waypoints.find("Waypoint01R"), 0, 0), MapError);
}
