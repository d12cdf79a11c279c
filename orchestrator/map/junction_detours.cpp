#include "map/junction_detours.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace orch {

namespace {

// m: the least connection left on either side of a detour lane (into it from the lane before,
// out of it to the lane after).
constexpr double kMinDetourConnection = 1.0;
// m: the shortest half of a detour lane (each of its two edges; the corridor planner cuts
// a lane no closer than 0.5 m).
constexpr double kMinDetourHalf = 0.55;

// One path through a junction between a pair of lanes: the first route's (its connection),
// or a detour's (the route that got the detour lane).
struct SharedPath {
  Polyline line;   // the route's points through the passage
  int detour = -1; // its detour lane (index into pieces), -1: the first path (no detour)
};

// The arc length on `route` of each of its waypoints inside passage p (a closed route's
// passage may run across its first point: s1 > length).
std::vector<std::pair<std::size_t, double>> waypoints_in(const WaypointRoute& route, const JunctionPassage& p) {
  const double length = route.line.length();
  const bool closed = is_closed_route(route);
  std::vector<std::pair<std::size_t, double>> out;
  for (std::size_t i = 0; i < route.points.size(); ++i) {
    const double s = route.line.s_at_index(i);
    if (s >= p.s0 && s <= p.s1) out.emplace_back(i, s);
    else if (closed && s + length >= p.s0 && s + length <= p.s1) out.emplace_back(i, s + length);
  }
  return out;
}

// The passage's points, cut exactly at its ends.
Polyline passage_line(const WaypointRoute& route, const JunctionPassage& p) {
  std::vector<Vec2> xy;
  for (const WaypointPoint& w : stretch(route, p.s0, p.s1)) xy.emplace_back(w.x, w.y);
  return Polyline(std::move(xy));
}

// The path its connection will take (junction_plan.cpp): from the end of the lane before
// through the passage's points to the start of the lane after (a route starting or ending
// inside the junction reaches the lane it is attached to this way).
Polyline connection_path(const WaypointRoute& route, const JunctionPassage& p, const Polyline& before,
                         const Polyline& after) {
  std::vector<Vec2> xy{before.points().back()};
  const Polyline inner = passage_line(route, p);
  // Through the route's own first (last) waypoint where it starts (ends) inside the junction
  // past the lane's end, as junction_plan.cpp's connection shape does.
  const bool open = !is_closed_route(route);
  const auto own_end = [&](bool start) {
    const Vec2& lane_end = start ? before.points().back() : after.point(0);
    const Polyline::Projection pr = route.line.project_near(lane_end, start ? p.s0 : p.s1, 5.0);
    return open && (start ? p.s0 <= 0 && pr.s <= 1e-6 : p.s1 >= route.line.length() && pr.s >= route.line.length() - 1e-6) &&
           ((start ? inner.point(0) : inner.points().back()) - lane_end).norm() > 0.05;
  };
  if (own_end(true)) xy.push_back(inner.point(0));
  for (std::size_t i = 1; i + 1 < inner.size(); ++i) xy.push_back(inner.point(i));
  if (own_end(false)) xy.push_back(inner.points().back());
  xy.push_back(after.point(0));
  return Polyline(std::move(xy)).simplified(kConnectionSimplify);
}

// The waypoint of the passage lying farthest from `path` (and from the lanes before and
// after, which its first and last waypoints may lie on): its arc length and distance.
std::pair<double, double> farthest_from(const WaypointRoute& route, const JunctionPassage& p, const Polyline& path,
                                        const Polyline& before, const Polyline& after) {
  std::pair<double, double> worst{(p.s0 + p.s1) / 2, 0.0};
  for (const auto& [i, s] : waypoints_in(route, p)) {
    const Vec2& q = route.line.point(i);
    const double d = std::min({path.project(q).distance, before.project(q).distance, after.project(q).distance});
    if (d > worst.second) worst = {s, d};
  }
  return worst;
}

// cos 150 deg: a route turning back on itself sharper than this at a waypoint draws a spike.
constexpr double kSpikeCos = -0.866;
constexpr double kSpikeLeg = 0.01;  // m: shorter legs are a repeated point, no direction

// Arc-length stretches of the route drawn out and back over itself: around each waypoint where
// it turns back (a 180-degree spike's tip, and the point where it turns forward again), as far
// as the shorter leg there. A detour lane cut inside one would run out and back (seed 200: its
// two halves met at the tip, the second pointing backwards, joined by a U-turn of no length).
std::vector<std::pair<double, double>> spike_stretches(const WaypointRoute& route) {
  std::vector<std::pair<double, double>> out;
  const Polyline& l = route.line;
  for (std::size_t i = 1; i + 1 < l.size(); ++i) {
    const Vec2 in = l.point(i) - l.point(i - 1);
    const Vec2 on = l.point(i + 1) - l.point(i);
    if (in.norm() < kSpikeLeg || on.norm() < kSpikeLeg || in.dot(on) > kSpikeCos * in.norm() * on.norm()) continue;
    const double leg = std::min(in.norm(), on.norm());
    out.emplace_back(l.s_at_index(i) - leg, l.s_at_index(i) + leg);
  }
  return out;
}

// The middle of a detour lane of half length `half` nearest to m in [lo, hi] whose lane
// [middle - half, middle + half] (arc lengths from the passage's start s0) crosses no spike;
// none: NaN.
double clear_of_spikes(const WaypointRoute& route, double s0, double m, double half, double lo, double hi) {
  const std::vector<std::pair<double, double>> spikes = spike_stretches(route);
  const auto clear = [&](double c) {
    return std::none_of(spikes.begin(), spikes.end(), [&](const auto& z) {
      return s0 + c + half > z.first && s0 + c - half < z.second;
    });
  };
  if (clear(m)) return m;
  // Candidates: just beyond either end of each spike stretch.
  double best = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [z0, z1] : spikes)
    for (const double c : {z1 - s0 + half + 0.01, z0 - s0 - half - 0.01})
      if (c >= lo && c <= hi && clear(c) && (std::isnan(best) || std::abs(c - m) < std::abs(best - m))) best = c;
  return best;
}

}  // namespace

void add_detour_lanes(const WaypointFile& wf, JunctionPieces& out) {
  // Passages by (lane before, lane after, junction), in driving order of the file's routes.
  std::map<std::tuple<int, int, int>, std::vector<std::size_t>> by_pair;
  for (std::size_t k = 0; k < out.passages.size(); ++k) {
    const JunctionPassage& p = out.passages[k];
    if (p.before >= 0 && p.after >= 0) by_pair[{p.before, p.after, p.zone}].push_back(k);
  }
  // Each passage replaced by its two halves around a detour lane (none: kept as it is).
  std::map<std::size_t, std::pair<JunctionPassage, JunctionPassage>> split;
  std::set<std::string> used_ids;
  for (const auto& [key, group] : by_pair) {
    if (group.size() < 2) continue;
    const Polyline before = out.pieces[static_cast<std::size_t>(std::get<0>(key))].line.line;
    const Polyline after = out.pieces[static_cast<std::size_t>(std::get<1>(key))].line.line;
    std::vector<SharedPath> paths;
    for (const std::size_t k : group) {
      const JunctionPassage& p = out.passages[k];
      const WaypointRoute& route = wf.routes[p.route];
      if (paths.empty()) {
        paths.push_back({connection_path(route, p, before, after), -1});
        continue;
      }
      // Along a path already there (within drawing noise): the route drives it.
      const SharedPath* along = nullptr;
      for (const SharedPath& path : paths)
        if (farthest_from(route, p, path.line, before, after).second <= kMaxSharedPathMiss) {
          along = &path;
          break;
        }
      if (along && along->detour < 0) continue;
      const Polyline line = passage_line(route, p);
      double a = 0;  // the detour lane's ends, arc lengths along the passage
      double b = 0;
      int detour = -1;
      if (along) {
        // Through the detour lane of the route it follows: cut at the feet of that lane's ends.
        RoutePiece& piece = out.pieces[static_cast<std::size_t>(along->detour)];
        a = line.project(piece.line.line.point(0)).s;
        b = line.project(piece.line.line.points().back()).s;
        const double least = std::min(kMinDetourConnection, line.length() / 5);
        if (a < least || b > line.length() - least || b <= a) continue;
        detour = along->detour;
        piece.routes.push_back(route.id);
      } else {
        // A path of its own: a detour lane where it lies farthest from the first path, kept
        // clear of the passage's ends so that both connections have a length.
        // (On a short passage, a route starting inside the junction, shorter connections.)
        const double connection = std::min(kMinDetourConnection, line.length() / 5);
        const double half = std::min(kDetourLength / 2, line.length() / 2 - connection);
        if (half < kMinDetourHalf) continue;
        const double lo = half + connection;
        const double hi = line.length() - lo;
        const double m = clear_of_spikes(
            route, p.s0, std::clamp(farthest_from(route, p, paths.front().line, before, after).first - p.s0, lo, hi),
            half, lo, hi);
        if (std::isnan(m)) continue;
        a = m - half;
        b = m + half;
        std::string id = fmt::format("{}.J{}", route.id, p.zone);
        for (int n = 2; used_ids.count(id); ++n) id = fmt::format("{}.J{}~{}", route.id, p.zone, n);
        used_ids.insert(id);
        RoutePiece piece{make_line(id, stretch(route, p.s0 + a, p.s0 + b)), p.route, {route.id}, p.zone, p.zone};
        piece.detour = true;
        detour = static_cast<int>(out.pieces.size());
        out.pieces.push_back(std::move(piece));
        paths.push_back({connection_path(route, p, before, after), detour});
      }
      JunctionPassage in = p;
      JunctionPassage on = p;
      in.s1 = p.s0 + a;
      in.after = detour;
      on.s0 = p.s0 + b;
      on.before = detour;
      if (const double length = route.line.length(); on.s0 >= length) {  // across a closed route's first point
        on.s0 -= length;
        on.s1 -= length;
      }
      split.emplace(k, std::make_pair(in, on));
    }
  }
  if (split.empty()) return;
  std::vector<JunctionPassage> passages;
  for (std::size_t k = 0; k < out.passages.size(); ++k) {
    const auto it = split.find(k);
    if (it == split.end()) {
      passages.push_back(out.passages[k]);
      continue;
    }
    passages.push_back(it->second.first);
    passages.push_back(it->second.second);
  }
  out.passages = std::move(passages);
}

}  // namespace orch
