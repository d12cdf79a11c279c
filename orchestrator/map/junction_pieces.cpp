#include "map/junction_pieces.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/checked_numeric.hpp"
#include "map/junction_detours.hpp"
#include "map/junction_path_fit.hpp"
#include "map/corridor_geometry.hpp"

namespace orch {

namespace {

constexpr double kContainSample = 2.0;   // m between the samples of the containment test
constexpr double kContainSlack = 0.5;    // m a contained piece may reach past the other's ends
constexpr double kContainDistance = 0.5; // m: noise between routes drawn "on the same lane"
constexpr double kContainCos = 0.94;     // cos 20 deg
// m: a route that ends (starts) inside a junction this close before (after) the start (end)
// of a lane it is drawn along continues on (comes from) that lane.
constexpr double kMaxEndGap = 3.0;
// m: the shortest dead-end lane (and connection) made for a route ending inside a junction.
// It was 1.0 m: routes ending 1.5-1.8 m into a junction (seeds 225, 286) then drove the
// connection of their lane's other route (or of their own earlier lap), 0.16-0.25 m off it.
constexpr double kMinLooseLane = 0.7;
// m: the same where the route lies off the path of every route going on through the junction
// on its lane, whose connection it would otherwise drive (seed 383: a route starting 1.2 m
// inside a junction beside the turn of a route going on along its lane, 0.30 m off it; 0.4 m
// until fix I: seed 606's route ends 0.69 m into a junction, 0.12 m off the only path there).
constexpr double kMinMisfitLooseLane = 0.3;
// m: points of a shared lane's best fit closer than this to the previous one are dropped
// (netconvert drops them from a lane's shape anyway).
constexpr double kSameStation = kNetconvertPointGap;

}  // namespace

// The points of `route` between arc lengths a < b (b may exceed the length of a closed
// route: the stretch then runs across its closing point), cut exactly at both ends.
std::vector<WaypointPoint> stretch(const WaypointRoute& route, double a, double b) {
  const double length = route.line.length();
  std::vector<WaypointPoint> out;
  const auto add = [&](double s) {
    const double w = s > length ? s - length : s;
    const Vec2 p = route.line.point_at(w);
    if (!out.empty() && std::hypot(out.back().x - p.x(), out.back().y - p.y()) < 1e-6) return;
    out.push_back({p.x(), p.y(), 0.0, route.speed_at(w)});
  };
  add(a);
  for (int lap = 0; lap < 2; ++lap)
    for (std::size_t i = 0; i < route.points.size(); ++i) {
      const double s = route.line.s_at_index(i) + lap * length;
      if (s > a + 1e-6 && s < b - 1e-6) add(s);
    }
  add(b);
  return out;
}

WaypointRoute make_line(std::string id, std::vector<WaypointPoint> pts) {
  WaypointRoute r;
  r.id = std::move(id);
  std::vector<Vec2> xy;
  for (const auto& p : pts) xy.emplace_back(p.x, p.y);
  r.points = std::move(pts);
  r.line = Polyline(std::move(xy));
  return r;
}

namespace {

// Whether piece `inner` lies along piece `outer` over its whole length, same direction.
bool lies_along(const RoutePiece& inner, const RoutePiece& outer) {
  const Polyline& a = inner.line.line;
  const Polyline& b = outer.line.line;
  const int n = pieces_covering(a.length(), kContainSample, 1, 1 << 30) + 1;
  for (int k = 0; k < n; ++k) {
    const double s = a.length() * k / (n - 1);
    const Polyline::Projection pr = b.project(a.point_at(s));
    if (pr.distance > kContainDistance) return false;
    const Vec2 foot = b.point_at(pr.s);
    if ((a.point_at(s) - foot).norm() > kContainSlack + kContainDistance) return false;  // beyond b's ends
    if (a.tangent_at(s).dot(b.tangent_at(pr.s)) < kContainCos) return false;
  }
  return true;
}

// Appends `p` to a lane's points unless it lies nearer than kSameStation to the last one kept
// (netconvert would drop it); the lane's `last` point stays, in place of the one kept before
// it. When that one is the lane's only point, `keep_two` keeps both (a line needs two points),
// else the last goes.
void add_station(std::vector<WaypointPoint>& pts, const WaypointPoint& p, bool last, bool keep_two) {
  if (!pts.empty() && std::hypot(pts.back().x - p.x, pts.back().y - p.y) < kSameStation) {
    if (!last) return;
    if (pts.size() >= 2) pts.pop_back();
    else if (!keep_two) return;
  }
  pts.push_back(p);
}

// The line of a lane shared by `owner` and the pieces drawn along it (`others`): the one that
// keeps every route's waypoints nearest. At each waypoint of any of them (not only the
// owner's: on a curve, another route's waypoints lie between the owner's, up to a chord's
// sagitta off its line) the lane goes through the middle of the routes farthest apart
// there, measured across the owner's direction (the midrange, which minimises the largest
// distance; a mean would leave a lone route on one side nearer 2/3 of the spread than 1/2).
// So routes drawn up to twice the fit tolerance apart "on one lane" all lie within it.
std::vector<WaypointPoint> shared_lane_points(const WaypointRoute& owner, const std::vector<const Polyline*>& others) {
  const Polyline& base = owner.line;
  std::vector<const Polyline*> all{&base};
  all.insert(all.end(), others.begin(), others.end());
  std::vector<std::pair<double, Vec2>> stations;  // arc length on the owner, lane point
  for (const Polyline* line : all)
    for (std::size_t i = 0; i < line->size(); ++i) {
      const Vec2& q = line->point(i);
      double s = base.s_at_index(std::min(i, base.size() - 1));
      if (line != &base) {
        const Polyline::Projection pr = base.project(q);
        // (The owner's first and last points stay the lane's ends.)
        if (pr.before_start || pr.after_end || pr.distance > kContainDistance || pr.s < kSameStation ||
            pr.s > base.length() - kSameStation)
          continue;
        s = pr.s;
      }
      const Vec2 n = left_normal(base.tangent_at(s));
      double lo = 0;  // offsets across, from q, of the routes there (q's own: 0)
      double hi = 0;
      for (const Polyline* other : all) {
        if (other == line) continue;
        // Short of its start (past its end, within kContainSlack: routes cut at one passage
        // end a few centimetres apart) its first (last) point counts, across the lane only.
        const Polyline::Projection po = other->project(q);
        if (po.distance > kContainDistance + (po.before_start || po.after_end ? kContainSlack : 0.0)) continue;
        const double o = (other->point_at(po.s) - q).dot(n);
        lo = std::min(lo, o);
        hi = std::max(hi, o);
      }
      stations.emplace_back(s, q + (lo + hi) / 2 * n);
    }
  std::stable_sort(stations.begin(), stations.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<WaypointPoint> pts;
  for (std::size_t k = 0; k < stations.size(); ++k) {
    const auto& [s, p] = stations[k];
    add_station(pts, {p.x(), p.y(), 0.0, owner.speed_at(s)}, k + 1 == stations.size(), false);
  }
  return pts;
}

// A route that ends inside a junction (its passage reaches its last waypoint) has no lane
// after it, so no connection carries its waypoints there and SUMO cannot drive it: it
// continues on the lane leaving that junction which its last waypoint lies on, or lies just
// before (within kMaxEndGap, along it). The same for a route that starts inside a junction,
// with the lane entering it. The route is then driven by that lane too.
void attach_loose_ends(const WaypointFile& wf, JunctionPieces& out) {
  for (JunctionPassage& jp : out.passages) {
    const WaypointRoute& route = wf.routes[jp.route];
    for (const bool at_end : {true, false}) {
      if ((at_end ? jp.after : jp.before) >= 0) continue;
      const Polyline& line = route.line;
      if (line.length() < 1.0) continue;
      const Vec2 p = at_end ? line.points().back() : line.point(0);
      // Directions over the last (first) metres: a route's last segment may be a few
      // centimetres of drawing noise pointing anywhere (seed 46: 3 cm at 31 degrees).
      const Vec2 dir = corridor::end_direction(line, at_end);
      int best = -1;
      double best_gap = kMaxEndGap;
      for (std::size_t k = 0; k < out.pieces.size(); ++k) {
        const RoutePiece& pc = out.pieces[k];
        if ((at_end ? pc.from_zone : pc.to_zone) != jp.zone || pc.line.line.length() < 1.0) continue;
        const Polyline& l = pc.line.line;
        const Polyline::Projection pr = l.project(p);
        // On the lane (beside it), or short of its start (past its end) straight along it.
        const Vec2 tip = at_end ? l.point(0) : l.points().back();
        const Vec2 along = corridor::end_direction(l, !at_end);
        if (pr.before_start || pr.after_end ? along.dot(dir) < kContainCos : l.tangent_at(pr.s).dot(dir) < kContainCos)
          continue;
        const double ahead = (tip - p).dot(along) * (at_end ? 1.0 : -1.0);  // > 0: p lies short of the lane
        double gap = 0;
        if (ahead > 0) {
          if (std::abs((p - tip).dot(left_normal(along))) > kContainDistance) continue;
          gap = ahead;
        } else if (pr.distance > kContainDistance || pr.before_start || pr.after_end) {
          continue;
        }
        // Drawn beside that lane (seed 5: a route ending 0.20 m beside the lane of one that made
        // the same turn) it would lie off it: a dead-end lane of its own fits it exactly.
        if (jp.s1 - jp.s0 >= 2 * kMinLooseLane && farthest_on(route, jp, l, at_end) > kLaneFit) continue;
        // Coming from (going on to) that lane, it would drive the connection of the routes
        // between that lane and its own; off their path (seed 615: a route starting 1.5 m into
        // a junction, 0.16 m beside the turn of a route coming from the lane before it, along
        // the lane after), a dead-end lane of its own fits it, where its passage has room for one.
        const int own = at_end ? jp.before : jp.after;
        if (own >= 0 && jp.s1 - jp.s0 >= 2 * kMinMisfitLooseLane &&
            !fits_a_path_between(wf, out.passages, jp, at_end ? own : static_cast<int>(k),
                                 at_end ? static_cast<int>(k) : own))
          continue;
        if (gap < best_gap || (best < 0 && gap <= best_gap)) {
          best = static_cast<int>(k);
          best_gap = gap;
        }
      }
      if (best < 0) continue;
      (at_end ? jp.after : jp.before) = best;
      auto& routes = out.pieces[static_cast<std::size_t>(best)].routes;
      if (std::find(routes.begin(), routes.end(), route.id) == routes.end()) routes.push_back(route.id);
    }
  }
}

// A route that still ends (starts) inside a junction, with no lane there to continue it
// (a street drawn to end on a crossing road, at the edge of the map), would leave its last
// (first) waypoints on no lane. Its own lane goes on to the route's end instead, as a dead
// end through that junction, when no other route drives that lane: the route takes no part
// in the junction, whose other routes are connected as before.
void end_lanes_in_junctions(const WaypointFile& wf, JunctionPieces& out) {
  // Per lane and end (true: the lane's end), the routes that end (start) inside the junction
  // there: when they are all the routes on that lane, the lane goes on through the junction
  // for all of them (routes drawn together from one start point inside a junction).
  std::map<std::pair<int, bool>, std::vector<std::string>> loose_on;
  std::map<std::pair<int, bool>, double> longest;  // their longest passage there
  for (const JunctionPassage& jp : out.passages) {
    const bool loose_end = jp.after < 0 && jp.before >= 0;
    const bool loose_start = jp.before < 0 && jp.after >= 0;
    if (!(loose_end || loose_start) || is_closed_route(wf.routes[jp.route])) continue;
    const std::pair<int, bool> key{loose_end ? jp.before : jp.after, loose_end};
    loose_on[key].push_back(wf.routes[jp.route].id);
    longest[key] = std::max(longest[key], jp.s1 - jp.s0);
  }
  std::vector<bool> extended(out.pieces.size(), false);
  std::vector<JunctionPassage> kept;
  for (const JunctionPassage& jp : out.passages) {
    const bool loose_end = jp.after < 0 && jp.before >= 0;
    const bool loose_start = jp.before < 0 && jp.after >= 0;
    const WaypointRoute& route = wf.routes[jp.route];
    const int k = loose_end ? jp.before : jp.after;
    if ((!loose_end && !loose_start) || is_closed_route(route)) {
      kept.push_back(jp);
      continue;
    }
    const std::vector<std::string>& together = loose_on[{k, loose_end}];
    const auto& on_lane = out.pieces[static_cast<std::size_t>(k)].routes;
    // Shared by several routes, the lane goes on only where their passage is too short for
    // dead-end lanes of their own (below): there they are drawn together.
    // A route on the lane that ends (starts) along it, before the junction, does not go on
    // through it (seed 208: the lane went nowhere, the route's last 2 m lay on no lane).
    const bool goes_on = std::any_of(out.passages.begin(), out.passages.end(), [&](const JunctionPassage& other) {
      return other.zone == jp.zone && (loose_end ? other.before == k && other.after >= 0
                                                 : other.after == k && other.before >= 0);
    });
    // A lane whose other end is at this junction too (the route's later lap comes back
    // through its own start, seed 734) cannot go on through it: netconvert cuts a lane where
    // its own junction's shape crosses it, and that shape reaches lane ends on both sides of it.
    const RoutePiece& lane_piece = out.pieces[static_cast<std::size_t>(k)];
    const bool returns = (loose_end ? lane_piece.from_zone : lane_piece.to_zone) == jp.zone;
    const bool all_loose = (on_lane.size() == 1 || longest[{k, loose_end}] < 2 * kMinLooseLane) &&
                           !goes_on && !together.empty() && !returns;
    if (extended[static_cast<std::size_t>(k)] && all_loose) continue;  // the lane already goes on for it
    if (!all_loose) {
      // Its lane is driven by other routes too, which go on through the junction: the route
      // gets a dead-end lane of its own for the second half of its passage (the first half
      // is its connection from the shared lane), or the first half when it starts there.
      const double shortest = fits_a_path_on(wf, out.passages, jp, k, loose_end) ? kMinLooseLane : kMinMisfitLooseLane;
      if (jp.s1 - jp.s0 >= 2 * shortest) {
        JunctionPassage cut = jp;
        const double mid = (jp.s0 + jp.s1) / 2;
        const int index = static_cast<int>(out.pieces.size());
        if (loose_end) {
          out.pieces.push_back({make_line(fmt::format("{}.end", route.id), stretch(route, mid, jp.s1)), jp.route,
                                {route.id}, jp.zone, -1, true});
          cut.s1 = mid;
          cut.after = index;
        } else {
          out.pieces.push_back({make_line(fmt::format("{}.start", route.id), stretch(route, jp.s0, mid)), jp.route,
                                {route.id}, -1, jp.zone, true});
          cut.s0 = mid;
          cut.before = index;
        }
        kept.push_back(cut);
        continue;
      }
      kept.push_back(jp);
      continue;
    }
    extended[static_cast<std::size_t>(k)] = true;
    RoutePiece& piece = out.pieces[static_cast<std::size_t>(k)];
    std::vector<WaypointPoint> pts = piece.line.points;
    if (loose_end) {
      std::vector<WaypointPoint> tail = stretch(route, jp.s0, route.line.length());
      pts.insert(pts.end(), tail.begin() + 1, tail.end());
      piece.to_zone = -1;
    } else {
      std::vector<WaypointPoint> head = stretch(route, 0.0, jp.s1);
      head.insert(head.end(), pts.begin() + 1, pts.end());
      pts = std::move(head);
      piece.from_zone = -1;
    }
    piece.line = make_line(piece.line.id, std::move(pts));
  }
  out.passages = std::move(kept);
}

}  // namespace

JunctionPieces cut_into_pieces(const WaypointFile& wf, const JunctionZones& zones) {
  JunctionPieces out;
  for (std::size_t r = 0; r < wf.routes.size(); ++r) {
    const WaypointRoute& route = wf.routes[r];
    const auto& ps = zones.passages[r];
    const double length = route.line.length();
    if (ps.empty()) {
      out.pieces.push_back({route, r, {route.id}, -1, -1});
      continue;
    }
    const bool closed = is_closed_route(route);
    // Pieces between consecutive passages; an open route also before the first and after
    // the last, a closed one from the last passage round to the first.
    std::vector<std::pair<double, double>> spans;
    std::vector<std::pair<int, int>> span_zones;
    if (!closed && ps.front().s0 > 0) {
      spans.emplace_back(0.0, ps.front().s0);
      span_zones.emplace_back(-1, ps.front().zone);
    }
    for (std::size_t i = 0; i + 1 < ps.size(); ++i) {
      spans.emplace_back(ps[i].s1, ps[i + 1].s0);
      span_zones.emplace_back(ps[i].zone, ps[i + 1].zone);
    }
    if (closed) {
      spans.emplace_back(ps.back().s1, ps.front().s0 + length);
      span_zones.emplace_back(ps.back().zone, ps.front().zone);
    } else if (ps.back().s1 < length) {
      spans.emplace_back(ps.back().s1, length);
      span_zones.emplace_back(ps.back().zone, -1);
    }
    const int first_piece = static_cast<int>(out.pieces.size());
    for (std::size_t k = 0; k < spans.size(); ++k) {
      auto [a, b] = spans[k];
      if (a >= length && closed) {
        a -= length;
        b -= length;
      }
      RoutePiece piece{make_line(fmt::format("{}.{}", route.id, k), stretch(route, a, b)), r, {route.id},
                       span_zones[k].first, span_zones[k].second};
      out.pieces.push_back(std::move(piece));
    }
    // Passages with the pieces on either side (a closed route's last piece leads into its first passage).
    const int pieces_here = static_cast<int>(spans.size());
    const int lead = (!closed && ps.front().s0 > 0) ? 1 : 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      JunctionPassage jp{r, ps[i].zone, ps[i].s0, ps[i].s1, -1, -1};
      const int before = static_cast<int>(i) - 1 + lead;
      const int after = static_cast<int>(i) + lead;
      if (closed) {
        jp.before = first_piece + (before + pieces_here) % pieces_here;
        jp.after = first_piece + after % pieces_here;
      } else {
        jp.before = before >= 0 ? first_piece + before : -1;
        jp.after = after < pieces_here ? first_piece + after : -1;
      }
      out.passages.push_back(jp);
    }
  }

  // Fold pieces drawn along another (longer) piece into it: one lane, several routes.
  std::vector<int> owner(out.pieces.size());
  for (std::size_t i = 0; i < owner.size(); ++i) owner[i] = static_cast<int>(i);
  std::vector<std::size_t> order(out.pieces.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return out.pieces[a].line.line.length() > out.pieces[b].line.line.length();
  });
  for (std::size_t oi = 0; oi < order.size(); ++oi) {
    const std::size_t q = order[oi];
    for (std::size_t pi = 0; pi < oi; ++pi) {
      const std::size_t p = order[pi];
      if (owner[p] != static_cast<int>(p)) continue;
      if (!lies_along(out.pieces[q], out.pieces[p])) continue;
      owner[q] = static_cast<int>(p);
      for (const auto& id : out.pieces[q].routes)
        if (std::find(out.pieces[p].routes.begin(), out.pieces[p].routes.end(), id) == out.pieces[p].routes.end())
          out.pieces[p].routes.push_back(id);
      ++out.merged;
      break;
    }
  }
  // A shared lane lies in the middle of the routes drawn along it: each point of the
  // longest one averaged with the feet on the others, so that routes drawn a few
  // centimetres apart "on one lane" are each only half as far from it. Where that leaves a
  // waypoint farther than kPlannedLaneMiss from it (routes drawn 0.1-0.15 m apart: on a
  // curve another route's waypoints lie between the longest one's, a chord's sagitta off
  // its line; three routes, one of them on its own on one side), the lane is the best fit
  // of them all instead (shared_lane_points), denser than the drawing.
  for (std::size_t p = 0; p < out.pieces.size(); ++p) {
    if (owner[p] != static_cast<int>(p)) continue;
    std::vector<const Polyline*> others;
    for (std::size_t q = 0; q < out.pieces.size(); ++q)
      if (q != p && owner[q] == static_cast<int>(p)) others.push_back(&out.pieces[q].line.line);
    if (others.empty()) continue;
    std::vector<WaypointPoint> pts = out.pieces[p].line.points;
    for (WaypointPoint& pt : pts) {
      Vec2 sum(pt.x, pt.y);
      int n = 1;
      for (const Polyline* o : others) {
        const Polyline::Projection pr = o->project(Vec2(pt.x, pt.y));
        if (pr.before_start || pr.after_end || pr.distance > kContainDistance) continue;
        sum += o->point_at(pr.s);
        ++n;
      }
      pt.x = sum.x() / n;
      pt.y = sum.y() / n;
    }
    // Points nearer than kSameStation to the one before go, as netconvert drops them: judged
    // with them, the line fitted a route it no longer fits in the net (seed 154: the lane's
    // second point, 2 cm after its first and moved 6 cm towards a route merging onto it).
    std::vector<WaypointPoint> kept_pts;
    for (std::size_t k = 0; k < pts.size(); ++k) add_station(kept_pts, pts[k], k + 1 == pts.size(), true);
    WaypointRoute averaged = make_line(out.pieces[p].line.id, std::move(kept_pts));
    const auto fits = [&](const Polyline& line) {
      return std::all_of(line.points().begin(), line.points().end(),
                         [&](const Vec2& q) { return averaged.line.project(q).distance <= kPlannedLaneMiss; });
    };
    const bool all_fit = fits(out.pieces[p].line.line) &&
                         std::all_of(others.begin(), others.end(), [&](const Polyline* o) { return fits(*o); });
    out.pieces[p].line = all_fit ? std::move(averaged)
                                 : make_line(out.pieces[p].line.id, shared_lane_points(out.pieces[p].line, others));
  }
  // Renumber: only owners remain.
  std::vector<int> index(out.pieces.size(), -1);
  std::vector<RoutePiece> kept;
  for (std::size_t i = 0; i < out.pieces.size(); ++i)
    if (owner[i] == static_cast<int>(i)) {
      index[i] = static_cast<int>(kept.size());
      kept.push_back(std::move(out.pieces[i]));
    }
  for (auto& jp : out.passages) {
    if (jp.before >= 0) jp.before = index[static_cast<std::size_t>(owner[static_cast<std::size_t>(jp.before)])];
    if (jp.after >= 0) jp.after = index[static_cast<std::size_t>(owner[static_cast<std::size_t>(jp.after)])];
  }
  out.pieces = std::move(kept);
  attach_loose_ends(wf, out);
  end_lanes_in_junctions(wf, out);
  // A route ending (starting) inside a junction with too short a passage for a dead-end lane
  // of its own, beside one drawn with it that got one (seed 165: two routes drawn to end
  // 0.5 m apart on one lane), continues on (comes from) that dead-end lane.
  attach_loose_ends(wf, out);
  add_detour_lanes(wf, out);
  return out;
}

}  // namespace orch
