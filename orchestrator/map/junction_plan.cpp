#include "map/junction_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "core/errors.hpp"
#include "map/corridor_cut_error.hpp"
#include "map/junction_detours.hpp"
#include "map/junction_pieces.hpp"
#include "map/junction_shape.hpp"
#include "map/junction_zones.hpp"
#include "map/lane_end_crossings.hpp"

namespace orch {

namespace {

constexpr int kOverridePriority = 100;
constexpr double kParallelCos = 0.9848;  // cos 10 deg

std::string junction_id(int zone) { return fmt::format("J{}", zone); }

struct LaneRef {
  std::size_t edge = 0;
  int lane = 0;
};


// The route's points from the lane end `from` to the lane start `to`, around arc lengths
// [s0, s1] of the passage (s1 may run past the end of a closed route).
std::vector<Vec2> passage_shape(const WaypointRoute& route, const JunctionPassage& p, const Vec2& from,
                                const Vec2& to) {
  const double length = route.line.length();
  const auto near = [&](const Vec2& q, double hint) {
    const double w = hint > length ? hint - length : hint;
    double s = route.line.project_near(q, w, 5.0).s;
    if (hint > length) s += length;
    return s;
  };
  const double a = near(from, p.s0);
  double b = near(to, p.s1);
  if (b < a) b += length;  // across a closed route's first point
  // A route starting (ending) inside the junction, attached to the lane before (after) it,
  // begins at its first waypoint, which lies past that lane's end: the path goes through it
  // (a chord from the lane end to the second waypoint missed it by 0.42 m on a curve, seed 130).
  const bool open = !is_closed_route(route);
  const auto own_end = [&](std::size_t i, const Vec2& lane_end) {
    return open && (route.line.point(i) - lane_end).norm() > 0.05;
  };
  std::vector<Vec2> pts{from};
  if (p.s0 <= 0 && a <= 1e-6 && own_end(0, from)) pts.push_back(route.line.point(0));
  for (int lap = 0; lap < 2; ++lap)
    for (std::size_t i = 0; i < route.line.size(); ++i) {
      const double s = route.line.s_at_index(i) + lap * length;
      // (A waypoint within 5 cm along of a lane end but beside it, 0.1 m or more from it, is
      // kept: a route attached to a lane that ends 0.12 m to its side, seed 142, left the
      // chord from the lane end to its next waypoint 0.11 m off it.)
      const Vec2& q = route.line.point(i);
      const bool apart = (q - from).norm() >= kNetconvertPointGap && (q - to).norm() >= kNetconvertPointGap;
      if ((s > a + 0.05 && s < b - 0.05) || (s > a && s < b && apart)) pts.push_back(q);
    }
  if (p.s1 >= length && b >= length - 1e-6 && own_end(route.line.size() - 1, to)) pts.push_back(route.line.points().back());
  pts.push_back(to);
  return Polyline(std::move(pts)).simplified(kConnectionSimplify).points();
}

// How far a free lane end may be extended straight (up to `wanted`) before the extension
// comes within a lane width of another route at an angle: a lane reaching into another
// road would put SUMO's vehicles on it on top of that road's.
double free_extension(const WaypointFile& wf, const RoutePiece& piece, bool start, double wanted) {
  const Polyline& line = piece.line.line;
  const Vec2 end = start ? line.point(0) : line.points().back();
  const double chord = std::min(2.0, line.length());
  const Vec2 dir = start ? Vec2((line.point(0) - line.point_at(chord)).normalized())
                         : Vec2((end - line.point_at(line.length() - chord)).normalized());
  for (double d = 1.0; d <= wanted + 1e-9; d += 1.0) {
    const Vec2 p = end + d * dir;
    for (const WaypointRoute& r : wf.routes) {
      const Polyline::Projection pr = r.line.project(p);
      if (pr.distance >= kConflictReach || pr.before_start || pr.after_end) continue;
      if (std::abs(r.line.tangent_at(pr.s).dot(dir)) > kParallelCos) continue;  // beside it: a neighbour
      return std::max(0.0, d - 1.0);
    }
  }
  return wanted;
}

class JunctionPlanner {
 public:
  JunctionPlanner(const WaypointFile& wf, const JunctionPieces& pieces, int zones, const JunctionSettings& js)
      : wf_(wf), pieces_(pieces), zones_(zones), settings_(js) {}

  void plan(NetPlan& plan) {
    index_lanes(plan);
    connect(plan);
    add_nodes(plan);
    apply_overrides(plan);
    plan.junctions = static_cast<int>(node_of_zone_.size());
  }

 private:
  // The first and last SUMO lane of every piece (edges are in driving order per corridor).
  void index_lanes(const NetPlan& plan) {
    for (std::size_t e = 0; e < plan.edges.size(); ++e)
      for (std::size_t l = 0; l < plan.edges[e].lanes.size(); ++l) {
        const int piece = plan.edges[e].lanes[l].piece;
        if (piece < 0) continue;
        first_.try_emplace(piece, LaneRef{e, static_cast<int>(l)});
        last_[piece] = LaneRef{e, static_cast<int>(l)};
      }
  }

  void connect(NetPlan& plan) {
    // (from edge, lane, to edge, lane) -> (its connection, the route whose points shape it)
    std::map<std::tuple<std::string, int, std::string, int>, std::pair<std::size_t, std::size_t>> seen;
    for (const JunctionPassage& p : pieces_.passages) {
      const WaypointRoute& route = wf_.routes[p.route];
      if (p.before < 0 || p.after < 0) {
        plan.notes.push_back(fmt::format("route \"{}\" {} inside junction {}: its waypoints there lie on no lane",
                                         route.id, p.before < 0 ? "starts" : "ends", junction_id(p.zone)));
        continue;
      }
      const auto from = last_.find(p.before);
      const auto to = first_.find(p.after);
      if (from == last_.end() || to == first_.end()) continue;
      const PlannedEdge& fe = plan.edges[from->second.edge];
      const PlannedEdge& te = plan.edges[to->second.edge];
      const auto key = std::make_tuple(fe.id, from->second.lane, te.id, to->second.lane);
      if (const auto it = seen.find(key); it != seen.end()) {
        check_same_path(plan.connections[it->second.first], wf_.routes[it->second.second], route, p,
                        {&fe.lanes[static_cast<std::size_t>(from->second.lane)].shape,
                         &te.lanes[static_cast<std::size_t>(to->second.lane)].shape},
                        plan.notes);
        continue;
      }
      seen[key] = {plan.connections.size(), p.route};
      const Vec2 a = fe.lanes[static_cast<std::size_t>(from->second.lane)].shape.points().back();
      const Vec2 b = te.lanes[static_cast<std::size_t>(to->second.lane)].shape.point(0);
      plan.connections.push_back({fe.id, te.id, from->second.lane, to->second.lane, passage_shape(route, p, a, b)});
      zone_used_[p.zone] = true;
    }
  }

  // SUMO has one connection per pair of lanes: a second route between the same lanes drives
  // the first one's path through the junction. Where it was drawn along another path (a
  // route leaning off its lane and back, a turn clipped by a short first leg, a shallow
  // 5-way junction) it has a detour lane of its own (junction_detours.hpp) unless its passage
  // is too short for one; then the net still carries it, connected, and `map build` notes how
  // far its waypoints lie from that path (`map check` measures them): refusing the map would
  // leave a user with no net for a drawing RoadEditor accepts.
  // `ends`: the lanes before and after, which a passage's first and last waypoints may lie on.
  void check_same_path(const PlannedConnection& c, const WaypointRoute& first, const WaypointRoute& route,
                       const JunctionPassage& p, const std::array<const Polyline*, 2>& ends,
                       std::vector<std::string>& notes) const {
    const Polyline path(c.shape);
    const double length = route.line.length();
    const bool closed = is_closed_route(route);  // only a closed route's passage wraps past its end
    double worst = 0;
    std::size_t worst_i = 0;
    for (std::size_t i = 0; i < route.points.size(); ++i) {
      const double s = route.line.s_at_index(i);
      if (!(s >= p.s0 && s <= p.s1) && !(closed && s + length >= p.s0 && s + length <= p.s1)) continue;
      const Vec2& q = route.line.point(i);
      const double d = std::min({path.project(q).distance, ends[0]->project(q).distance, ends[1]->project(q).distance});
      if (d > worst) {
        worst = d;
        worst_i = i;
      }
    }
    if (worst > kMaxSharedPathMiss)
      notes.push_back(fmt::format(
          "routes \"{}\" and \"{}\" both drive from lane {}_{} to lane {}_{} through junction {} along different "
          "paths; SUMO has one connection per pair of lanes, so \"{}\" drives \"{}\"'s path there (its wp_idx {} "
          "({:.2f}, {:.2f}) lies {:.2f} m from it)",
          first.id, route.id, c.from, c.from_lane, c.to, c.to_lane, junction_id(p.zone), route.id, first.id, worst_i,
          route.line.point(worst_i).x(), route.line.point(worst_i).y(), worst));
  }

  // One node per zone: at the middle of the lane ends it joins, shaped as the star polygon
  // through their corners; where that would cut one of its lanes (a lane leaving in the
  // middle of a turn, curving across the line to its neighbour's corner), through the lane
  // ends' centres instead, there and back through them, or out from the middle to each lane
  // end and back (spokes), whichever cuts least.
  void add_nodes(NetPlan& plan) {
    for (int z = 0; z < zones_; ++z) {
      const std::string id = junction_id(z);
      std::vector<Vec2> corners;
      std::vector<Vec2> centres;
      std::vector<LaneEnd> ends;
      Vec2 sum(0, 0);
      for (const PlannedEdge& e : plan.edges) {
        const bool in = e.to == id;
        const bool out = e.from == id;
        if (!in && !out) continue;
        for (const PlannedLane& l : e.lanes) {
          const Vec2 p = in ? l.shape.points().back() : l.shape.point(0);
          const Vec2 n = left_normal(l.shape.tangent_at(in ? l.shape.length() : 0.0));
          corners.push_back(p + l.width / 2 * n);
          corners.push_back(p - l.width / 2 * n);
          centres.push_back(p);
          ends.push_back({&l.shape, in});
          sum += p;
        }
      }
      if (ends.empty()) continue;
      PlannedNode node;
      node.id = id;
      node.position = sum / static_cast<double>(ends.size());
      node.shape = star_polygon(corners, node.position);
      if (convex_hull(corners).size() < 3) {  // lanes meeting end to end in a line: there and back
        node.shape = corners;
        node.shape.insert(node.shape.end(), corners.rbegin() + 1, corners.rend());
      }
      // Where a lane ends on the next one's start (a road split at the junction with no
      // passage of its own), the other shapes put a vertex where they meet and netconvert's
      // internal lane between the two has no length: there the star of corners stays.
      const bool end_on_start = std::any_of(ends.begin(), ends.end(), [&](const LaneEnd& a) {
        return a.incoming && std::any_of(ends.begin(), ends.end(), [&](const LaneEnd& b) {
                 return !b.incoming && (a.shape->points().back() - b.shape->point(0)).norm() < kSamePoint;
               });
      });
      if (double cut = cut_length(node.shape, ends); cut > 0 && !end_on_start) {
        const std::vector<Vec2> star = star_polygon(centres, node.position);
        std::vector<Vec2> spokes;  // from the middle out to each lane end and back
        for (const Vec2& p : star) {
          spokes.push_back(node.position);
          spokes.push_back(p);
        }
        for (const std::vector<Vec2>& other : {star, there_and_back(star), spokes}) {
          if (other.size() < 2) continue;
          const double c = cut_length(other, ends);
          if (c < cut) {
            cut = c;
            node.shape = other;
          }
        }
      }
      if (cut_length(node.shape, ends) > 0) {
        // Every shape above cuts a lane (lanes ending at very different places: a branch
        // along a curve, a dead-end lane inside the junction): a tree that cuts none.
        std::vector<TreeNode> tree;
        for (std::size_t i = 0; i < ends.size(); ++i) {
          const LaneEnd& a = ends[i];
          const Vec2 p = a.incoming ? a.shape->points().back() : a.shape->point(0);
          const bool shared = std::any_of(ends.begin(), ends.end(), [&](const LaneEnd& b) {
            return &b != &a && b.incoming != a.incoming &&
                   (p - (b.incoming ? b.shape->points().back() : b.shape->point(0))).norm() < kSamePoint;
          });
          if (!shared) {
            tree.push_back({p, {}});
            continue;
          }
          // Its corners, shared with a neighbouring lane's (or the lane it continues) where they meet.
          const auto corner = [&](const Vec2& c) {
            for (std::size_t k = 0; k < tree.size(); ++k)
              if ((tree[k].p - c).norm() <= kSamePoint) return k;
            tree.push_back({c, {}});
            return tree.size() - 1;
          };
          // Across the lane a little before its end (within kMaxShapeCut): netconvert's
          // internal lane between the two then has a length (a shape through the meeting point
          // itself would give it none).
          const double length = a.shape->length();
          const double at = a.incoming ? length - std::min(kEndOnStartCut, length / 2) : std::min(kEndOnStartCut, length / 2);
          const Vec2 q = a.shape->point_at(at);
          const Vec2 across = left_normal(a.shape->tangent_at(at)) * (corners[2 * i] - corners[2 * i + 1]).norm() / 2;
          const std::size_t c0 = corner(q + across);
          const std::size_t c1 = corner(q - across);
          if (c0 == c1) continue;
          if (std::find(tree[c0].partners.begin(), tree[c0].partners.end(), c1) == tree[c0].partners.end()) {
            tree[c0].partners.push_back(c1);
            tree[c1].partners.push_back(c0);
          }
        }
        tree.push_back({node.position, {}});
        if (std::vector<Vec2> t = uncut_tree(tree, ends); !t.empty() && cut_length(t, ends) == 0) node.shape = t;
      }
      node.type = "priority";
      node_of_zone_[z] = plan.nodes.size();
      plan.nodes.push_back(std::move(node));
    }
  }

  void apply_overrides(NetPlan& plan) {
    for (const JunctionOverride& o : settings_.overrides) {
      PlannedNode* node = find_node(plan, o);
      if (!o.type.empty()) node->type = o.type;
      for (PlannedEdge& e : plan.edges) {
        if (e.from != node->id && e.to != node->id) continue;
        for (const PlannedLane& l : e.lanes) {
          const auto& routes = l.routes.empty() ? std::vector<std::string>{l.route_id} : l.routes;
          const bool prior = std::any_of(routes.begin(), routes.end(), [&](const std::string& r) {
            return std::find(o.priority_routes.begin(), o.priority_routes.end(), r) != o.priority_routes.end();
          });
          if (prior) e.priority = kOverridePriority + static_cast<int>(e.lanes.size());
        }
      }
    }
  }

  PlannedNode* find_node(NetPlan& plan, const JunctionOverride& o) const {
    PlannedNode* best = nullptr;
    double best_d = kJunctionPickRadius;
    for (auto& [z, i] : node_of_zone_) {
      PlannedNode& n = plan.nodes[i];
      if (!o.id.empty() && n.id == o.id) return &n;
      if (o.at && (n.position - *o.at).norm() <= best_d) {
        best_d = (n.position - *o.at).norm();
        best = &n;
      }
    }
    if (best) return best;
    if (!o.id.empty()) throw MapError(fmt::format("map.json names junction \"{}\", which the net does not have", o.id));
    throw MapError(fmt::format("map.json names a junction at ({:.1f}, {:.1f}), but none lies within {:.0f} m",
                               o.at->x(), o.at->y(), kJunctionPickRadius));
  }

  const WaypointFile& wf_;
  const JunctionPieces& pieces_;
  int zones_;
  const JunctionSettings& settings_;
  std::map<int, LaneRef> first_;
  std::map<int, LaneRef> last_;
  std::map<int, bool> zone_used_;
  std::map<int, std::size_t> node_of_zone_;
};

}  // namespace

NetPlan plan_net(const WaypointFile& waypoints, const NetPlanSettings& settings) {
  return plan_net(waypoints, settings, JunctionSettings{});
}

NetPlan plan_net(const WaypointFile& waypoints, const NetPlanSettings& settings, const JunctionSettings& junctions) {
  NetPlan plan;
  const JunctionZones zones = find_junction_zones(waypoints);
  const JunctionPieces pieces = cut_into_pieces(waypoints, zones);
  if (zones.empty() && pieces.merged == 0) {
    if (!junctions.overrides.empty()) throw MapError("map.json sets junctions, but the routes form none");
    try {
      plan_corridors(waypoints, nullptr, settings, plan);  // roads only: corridors as they are
    } catch (const CorridorCutError& e) {
      throw name_waypoint(e, waypoints.routes[e.line()]);
    }
    secure_lane_end_crossings(plan);
    return plan;
  }
  WaypointFile lines;
  lines.path = waypoints.path;
  std::vector<CorridorLine> info;
  for (const RoutePiece& p : pieces.pieces) {
    lines.routes.push_back(p.line);
    info.push_back({p.routes, p.from_zone >= 0 ? junction_id(p.from_zone) : "",
                    p.to_zone >= 0 ? junction_id(p.to_zone) : "",
                    p.from_zone >= 0 ? -1.0 : free_extension(waypoints, p, true, settings.lane_extension),
                    p.to_zone >= 0 ? -1.0 : free_extension(waypoints, p, false, settings.lane_extension),
                    p.loose_end || p.detour});
  }
  try {
    plan_corridors(lines, &info, settings, plan);
  } catch (const CorridorCutError& e) {
    throw name_waypoint(e, waypoints.routes[pieces.pieces[e.line()].route]);
  }
  JunctionPlanner(waypoints, pieces, zones.count, junctions).plan(plan);
  secure_lane_end_crossings(plan);  // last: after every node's shape
  if (pieces.merged > 0)
    plan.notes.push_back(fmt::format("{} stretches of routes drawn along another route's lane share its lane",
                                     pieces.merged));
  return plan;
}

}  // namespace orch
