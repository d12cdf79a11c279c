// LaneMap::walk: a route of a junction map followed through SUMO's lane graph. The route's
// first waypoint lies on one of the lanes built for it; from there each waypoint stays on
// the current lane until it lies past the lane's end, and then moves on to the successor
// (an internal lane through a junction, or the next edge's lane) that the next few metres
// of the route follow best, among those that lead to a lane built for this route. The
// result is the route's lane sequence (loops and second passes included) with every
// waypoint placed on the lane that drives it there, junction interiors too.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "map/lane_map.hpp"

namespace orch {

namespace {

constexpr double kLookahead = 6.0;     // m of route that decides between successors
constexpr double kMaxMiss = 1.0;       // m: farther from every successor, the path is broken
constexpr int kMaxChain = 4;           // lanes followed ahead when scoring a successor
constexpr double kStartTie = 0.10;     // m: lanes this much farther from the first waypoint may start it
// m: successors scoring this close are told apart over a longer stretch of the route (two
// paths through a junction that part only after the first kLookahead metres: a detour lane)
constexpr double kScoreTie = 0.05;
constexpr int kMaxLookaheadDoublings = 3;

bool drives(const LaneInfo& lane, const std::string& route) {
  return std::find(lane.routes.begin(), lane.routes.end(), route) != lane.routes.end();
}

}  // namespace

RouteLanes LaneMap::walk(const WaypointRoute& route, const std::string& net_file) const {
  const auto beyond_end = [&](int lane, const Vec2& p) {
    const Polyline::Projection pr = lanes_[static_cast<std::size_t>(lane)].shape.project(p);
    return pr.after_end || pr.s >= lanes_[static_cast<std::size_t>(lane)].shape.length() - 1e-6;
  };
  // Does lane `l` lead (through internal lanes) to a normal lane built for this route?
  const auto leads_to_route = [&](int l) {
    for (int depth = 0; depth < kMaxChain; ++depth) {
      const LaneInfo& info = lanes_[static_cast<std::size_t>(l)];
      if (!info.internal) return drives(info, route.id);
      if (info.next.empty()) return false;
      l = info.next.front();
    }
    return false;
  };
  // Mean distance of the route's next kLookahead metres from waypoint i to the chain
  // starting at lane `l` (each point on the first lane of the chain it does not lie beyond).
  const auto score = [&](int l, std::size_t i, double lookahead = kLookahead) {
    const double s0 = route.line.s_at_index(i);
    double sum = 0;
    int n = 0;
    int lane = l;
    for (std::size_t j = i; j < route.points.size() && route.line.s_at_index(j) <= s0 + lookahead; ++j) {
      const Vec2& p = route.line.point(j);
      for (int depth = 0; depth < kMaxChain && beyond_end(lane, p); ++depth) {
        const auto& next = lanes_[static_cast<std::size_t>(lane)].next;
        const auto it = std::find_if(next.begin(), next.end(), [&](int x) { return leads_to_route(x); });
        if (it == next.end()) break;
        lane = *it;
      }
      sum += place_on_lane(lane, p).distance;
      ++n;
    }
    return n > 0 ? sum / n : std::numeric_limits<double>::infinity();
  };

  RouteLanes rl;
  rl.route_id = route.id;
  std::vector<int> own;
  for (std::size_t i = 0; i < lanes_.size(); ++i)
    if (!lanes_[i].internal && drives(lanes_[i], route.id)) own.push_back(static_cast<int>(i));
  if (own.empty())
    throw MapError(fmt::format("route \"{}\" has no lanes in {}: the net was not built from this waypoint file (run "
                               "`orchestrator map build`)", route.id, net_file));
  // The first lane: the nearest of the route's own lanes, unless another one it lies on as
  // well (within kStartTie) follows its first metres better: a route that ends (or passes
  // again) where it began lies on two of its lanes there, and only one of them starts it.
  const LanePlace nearest = nearest_of(own, route.line.point(0));
  int lane = nearest.lane;
  double best_start = score(lane, 0);
  for (const int l : own) {
    if (l == nearest.lane || place_on_lane(l, route.line.point(0)).distance > nearest.distance + kStartTie) continue;
    const double sc = score(l, 0);
    if (sc < best_start - 1e-9) {
      best_start = sc;
      lane = l;
    }
  }
  rl.lanes.push_back(lane);
  for (std::size_t i = 0; i < route.points.size(); ++i) {
    const Vec2& p = route.line.point(i);
    while (beyond_end(lane, p) && !lanes_[static_cast<std::size_t>(lane)].next.empty()) {
      int best = -1;
      double best_score = std::numeric_limits<double>::infinity();
      std::vector<std::pair<int, double>> scored;
      for (const int next : lanes_[static_cast<std::size_t>(lane)].next) {
        if (!leads_to_route(next)) continue;
        const double sc = score(next, i);
        scored.emplace_back(next, sc);
        if (sc < best_score) {
          best_score = sc;
          best = next;
        }
      }
      // Tied successors (their paths coincide over the lookahead): a longer stretch of the
      // route decides, when it tells them apart by more than kScoreTie.
      double lookahead = kLookahead;
      for (int round = 0; round < kMaxLookaheadDoublings; ++round) {
        std::vector<int> tied;
        for (const auto& [next, sc] : scored)
          if (sc <= best_score + kScoreTie) tied.push_back(next);
        if (tied.size() < 2) break;
        lookahead *= 2;
        scored.clear();
        for (const int next : tied) scored.emplace_back(next, score(next, i, lookahead));
        const auto current = std::find_if(scored.begin(), scored.end(), [&](const auto& x) { return x.first == best; });
        const auto least = std::min_element(scored.begin(), scored.end(),
                                            [](const auto& a, const auto& b) { return a.second < b.second; });
        if (least->second < current->second - kScoreTie) {
          best = least->first;
          best_score = least->second;
        } else {
          best_score = current->second;
        }
      }
      if (best >= 0) best_score = score(best, i);
      if (best < 0 || best_score > kMaxMiss) {
        if (i + 1 == route.points.size()) break;  // the last waypoint may lie past the last lane
        throw MapError(fmt::format(
            "route \"{}\" cannot be driven as one connected path: at wp_idx {} ({:.2f}, {:.2f}) it leaves lane \"{}\" "
            "and no lane that continues it follows the route{}",
            route.id, i, p.x(), p.y(), lanes_[static_cast<std::size_t>(lane)].id,
            best < 0 ? "" : fmt::format(" (nearest {:.2f} m away)", best_score)));
      }
      lane = best;
      rl.lanes.push_back(lane);
    }
    rl.points.push_back(place_on_lane(lane, p));
    rl.visits.push_back(static_cast<int>(rl.lanes.size()) - 1);
  }
  return rl;
}

}  // namespace orch
