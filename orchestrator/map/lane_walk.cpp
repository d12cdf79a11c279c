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
constexpr double kOffLane = 0.10;      // m: farther from its lane, a waypoint may have left it (map check's tolerance)
constexpr double kStartTie = 0.10;     // m: lanes this much farther from the first waypoint may start it
// m: successors scoring this close are told apart over a longer stretch of the route (two
// paths through a junction that part only after the first kLookahead metres: a detour lane)
constexpr double kScoreTie = 0.05;
constexpr int kMaxLookaheadDoublings = 3;
// m: of successors still tied, one whose farthest waypoint lies this much nearer is taken
constexpr double kFarthestTie = 0.01;

bool drives(const LaneInfo& lane, const std::string& route) {
  return std::find(lane.routes.begin(), lane.routes.end(), route) != lane.routes.end();
}

// The internal lane after `lane` that the route's waypoints from i to its last lie on, or -1.
int ending_lane(const LaneMap& map, int lane, const WaypointRoute& route, std::size_t i) {
  const std::vector<LaneInfo>& lanes = map.lanes();
  int best = -1;
  double best_sum = std::numeric_limits<double>::infinity();
  for (const int next : lanes[static_cast<std::size_t>(lane)].next) {
    const LaneInfo& info = lanes[static_cast<std::size_t>(next)];
    if (!info.internal) continue;
    double sum = 0;
    for (std::size_t j = i; j < route.points.size() && sum < best_sum; ++j) {
      const Polyline::Projection pr = info.shape.project(route.line.point(j));
      if (pr.after_end || pr.distance > kMaxMiss) {
        sum = std::numeric_limits<double>::infinity();
        break;
      }
      sum += pr.distance;
    }
    if (sum < best_sum) {
      best_sum = sum;
      best = next;
    }
  }
  return best;
}

// The internal lane before `lane` (the route's first) that its first waypoints lie on, or -1.
int starting_lane(const LaneMap& map, int lane, const WaypointRoute& route) {
  const std::vector<LaneInfo>& lanes = map.lanes();
  const auto place_on_lane = [&](int l, const Vec2& p) { return map.place_on_lane(l, p); };
  const double off = place_on_lane(lane, route.line.point(0)).distance;
  int best = -1;
  double best_mean = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < lanes.size(); ++k) {
    const LaneInfo& info = lanes[k];
    if (!info.internal || std::find(info.next.begin(), info.next.end(), lane) == info.next.end()) continue;
    double sum = 0;
    int n = 0;
    for (std::size_t j = 0; j < route.points.size(); ++j, ++n) {
      const Polyline::Projection pr = info.shape.project(route.line.point(j));
      if (pr.after_end || pr.s >= info.shape.length() - 1e-6) break;  // on the first lane from here
      if (pr.distance > kMaxMiss) {
        sum = std::numeric_limits<double>::infinity();
        break;
      }
      sum += pr.distance;
    }
    if (n == 0 || !(sum / n < best_mean) || place_on_lane(static_cast<int>(k), route.line.point(0)).distance >= off)
      continue;
    best_mean = sum / n;
    best = static_cast<int>(k);
  }
  return best;
}

// Of the candidate first lanes `starts`, the one the route follows best: `best` (scoring
// `best_score` over the first kLookahead metres) unless a candidate tied with it there (within
// kScoreTie) follows the route better by more than kScoreTie over a longer stretch (doubled
// until they part or the stretch is the whole route). Two lanes lying on each other where the
// route starts (its later lap along its first stretch: seed 479, one of them ends 11 m on at a
// dead end, the other goes on; seed 888, 130 m on) are told apart only where they part.
template <typename Score>
int untie_start(const std::vector<int>& starts, int best, double best_score, double route_length, const Score& score) {
  std::vector<int> tied;
  for (const int l : starts)
    if (l == best || score(l, 0) <= best_score + kScoreTie) tied.push_back(l);
  for (double lookahead = kLookahead; tied.size() > 1 && lookahead < route_length;) {
    lookahead *= 2;
    std::vector<std::pair<int, double>> scored;
    for (const int l : tied) scored.emplace_back(l, score(l, 0, false, lookahead));
    const auto current = std::find_if(scored.begin(), scored.end(), [&](const auto& x) { return x.first == best; });
    const auto least = std::min_element(scored.begin(), scored.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
    const double current_score = current->second;
    if (least->second < current_score - kScoreTie) best = least->first;
    const double bar = std::min(current_score, least->second) + kScoreTie;
    tied.clear();
    for (const auto& [l, sc] : scored)
      if (l == best || sc <= bar) tied.push_back(l);
  }
  return best;
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
  // Mean distance of the route's next metres (see `whole`) from waypoint i to the chain
  // starting at lane `l` (each point on the first lane of the chain it does not lie beyond);
  // with `farthest`, the largest distance instead.
  const auto score = [&](int l, std::size_t i, bool whole = false, double lookahead = kLookahead,
                         bool farthest = false) {
    const double s0 = route.line.s_at_index(i);
    const LaneInfo& first = lanes_[static_cast<std::size_t>(l)];
    const double ahead = lookahead + (whole && first.internal ? first.shape.length() : 0.0);
    double sum = 0;
    int n = 0;
    int lane = l;
    for (std::size_t j = i; j < route.points.size() && route.line.s_at_index(j) <= s0 + ahead; ++j) {
      const Vec2& p = route.line.point(j);
      for (int depth = 0; depth < kMaxChain && beyond_end(lane, p); ++depth) {
        const auto& next = lanes_[static_cast<std::size_t>(lane)].next;
        const auto it = std::find_if(next.begin(), next.end(), [&](int x) { return leads_to_route(x); });
        if (it == next.end()) break;
        lane = *it;
      }
      const double d = place_on_lane(lane, p).distance;
      sum = farthest ? std::max(sum, d) : sum + d;
      ++n;
    }
    if (n == 0) return std::numeric_limits<double>::infinity();
    return farthest ? sum : sum / n;
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
  std::vector<int> starts{lane};
  for (const int l : own) {
    if (l == nearest.lane || place_on_lane(l, route.line.point(0)).distance > nearest.distance + kStartTie) continue;
    starts.push_back(l);
    const double sc = score(l, 0);
    if (sc < best_start - 1e-9) {
      best_start = sc;
      lane = l;
    }
  }
  lane = untie_start(starts, lane, best_start, route.line.length(), score);
  // A route that starts a metre or two inside a junction, along the connection of routes
  // that come through it onto its first lane, starts on that connection's internal lane.
  if (place_on_lane(lane, route.line.point(0)).distance > kOffLane) {
    if (const int start = starting_lane(*this, lane, route); start >= 0) {
      lane = start;
    } else {
      // Not into the nearest of its lanes: a route starting inside a junction that its own
      // later lap passes (seed 130) lies nearest to that lap's detour lane, but starts on the
      // connection into another of its lanes.
      double best = place_on_lane(lane, route.line.point(0)).distance;
      for (const int l : own)
        if (const int st = starting_lane(*this, l, route); st >= 0) {
          const double d = place_on_lane(st, route.line.point(0)).distance;
          if (d < best) {
            best = d;
            lane = st;
          }
        }
    }
  }
  rl.lanes.push_back(lane);
  for (std::size_t i = 0; i < route.points.size(); ++i) {
    const Vec2& p = route.line.point(i);
    // Off its lane before the lane's end: where a lane ends inside a 180-degree spike of the
    // route (the line overshoots and comes back), the points after the spike lie nearest to
    // its tip, inside the lane, though the route has gone on into the junction (seed 90). It
    // moves on when a successor carries the next metres better than the lane carries this point.
    if (const double off = place_on_lane(lane, p).distance; off > kOffLane && !beyond_end(lane, p)) {
      int best = -1;
      double best_score = off;
      for (const int next : lanes_[static_cast<std::size_t>(lane)].next) {
        // The point itself lies beside the successor, nearer than to the lane (not short of
        // its start: a route drawn off a connection it shares is no reason to leave it early).
        const Polyline::Projection pr = lanes_[static_cast<std::size_t>(next)].shape.project(p);
        if (!leads_to_route(next) || pr.before_start || pr.distance >= off) continue;
        const double sc = score(next, i);
        if (sc < best_score) {
          best_score = sc;
          best = next;
        }
      }
      if (best >= 0) {
        lane = best;
        rl.lanes.push_back(lane);
      }
    }
    while (beyond_end(lane, p) && !lanes_[static_cast<std::size_t>(lane)].next.empty()) {
      // Successors are chosen on the route's next metres through the whole internal lane (two
      // connections that run together for 20 m and then part, seed 31) ...
      int best = -1;
      double best_score = std::numeric_limits<double>::infinity();
      double best_whole = std::numeric_limits<double>::infinity();
      std::vector<std::pair<int, double>> scored;
      for (const int next : lanes_[static_cast<std::size_t>(lane)].next) {
        if (!leads_to_route(next)) continue;
        const double whole = score(next, i, true);
        scored.emplace_back(next, whole);
        if (whole < best_whole) {
          best_whole = whole;
          best = next;
        }
      }
      // ... and tied ones (their paths coincide over that stretch: a detour lane parting later)
      // over a longer stretch of the route, when it tells them apart by more than kScoreTie.
      double lookahead = kLookahead;
      for (int round = 0; round < kMaxLookaheadDoublings && best >= 0; ++round) {
        std::vector<int> tied;
        for (const auto& [next, sc] : scored)
          if (sc <= best_whole + kScoreTie) tied.push_back(next);
        if (tied.size() < 2) break;
        lookahead *= 2;
        scored.clear();
        for (const int next : tied) scored.emplace_back(next, score(next, i, true, lookahead));
        const auto current = std::find_if(scored.begin(), scored.end(), [&](const auto& x) { return x.first == best; });
        const auto least = std::min_element(scored.begin(), scored.end(),
                                            [](const auto& a, const auto& b) { return a.second < b.second; });
        if (least->second < current->second - kScoreTie) {
          best = least->first;
          best_whole = least->second;
        } else {
          best_whole = current->second;
        }
      }
      // Still tied (a route drawn between two paths that run together into the same lane, seed
      // 480: between a connection and the detour lane of another route's turn, 0.04 m from
      // either on average), the one that leaves the route's farthest waypoint nearest to it:
      // `map check` holds every waypoint within kOffLane, not their mean.
      if (best >= 0) {
        double best_farthest = std::numeric_limits<double>::quiet_NaN();
        for (const auto& [next, sc] : scored) {
          if (next == best || sc > best_whole + kScoreTie) continue;
          if (std::isnan(best_farthest)) best_farthest = score(best, i, true, lookahead, true);
          if (const double f = score(next, i, true, lookahead, true); f < best_farthest - kFarthestTie) {
            best = next;
            best_farthest = f;
          }
        }
      }
      if (best >= 0) best_score = score(best, i);
      // A route ending inside the junction, its last waypoints off every connection that
      // leads to its own lanes, ends on the one of them all (another route's) they lie on
      // (seed 62: a route ending 0.5 m into a junction, 0.19 m off the connection of its
      // lane's other route, 0.06 m off a third one's).
      if (best >= 0 && best_score > kOffLane) {
        if (const int end = ending_lane(*this, lane, route, i); end >= 0 && end != best) {
          double sum = 0;
          for (std::size_t j = i; j < route.points.size(); ++j)
            sum += lanes_[static_cast<std::size_t>(end)].shape.project(route.line.point(j)).distance;
          if (sum / static_cast<double>(route.points.size() - i) < best_score) {
            lane = end;
            rl.lanes.push_back(lane);
            continue;
          }
        }
      }
      if (best < 0 || best_score > kMaxMiss) {
        if (i + 1 == route.points.size()) {
          // The last waypoint may lie past the last lane; where it lies nearer a connection out
          // of that lane (another route's, seed 993: a route ending 0.28 m into a junction, 0.02 m
          // off the connection of the routes that go on straight), it ends on that one.
          if (const int end = ending_lane(*this, lane, route, i);
              end >= 0 && place_on_lane(end, p).distance < place_on_lane(lane, p).distance) {
            lane = end;
            rl.lanes.push_back(lane);
          }
          break;
        }
        // A route that ends a metre or two inside a junction, along the connection of routes
        // that go on through it, ends on that connection's internal lane (SUMO stops it at
        // the end of the lane before, as any end inside a junction).
        if (const int end = ending_lane(*this, lane, route, i); end >= 0) {
          lane = end;
          rl.lanes.push_back(lane);
          continue;
        }
        throw MapError(fmt::format(
            "route \"{}\" cannot be driven as one connected path: at wp_idx {} ({:.2f}, {:.2f}) it leaves lane \"{}\" "
            "and no lane that continues it follows the route{}",
            route.id, i, p.x(), p.y(), lanes_[static_cast<std::size_t>(lane)].id,
            best < 0 ? "" : fmt::format(" (nearest {:.2f} m away)", best_score)));
      }
      lane = best;
      rl.lanes.push_back(lane);
    }
    // Past the end of a lane that leads nowhere (a dead end): the route goes on where no lane
    // carries it. Measured against that lane's end it would read as a waypoint far off its
    // lane; it is a break of the path (the last waypoint may lie past the last lane).
    if (i + 1 < route.points.size() && beyond_end(lane, p) && lanes_[static_cast<std::size_t>(lane)].next.empty() &&
        place_on_lane(lane, p).distance > kMaxMiss)
      throw MapError(fmt::format(
          "route \"{}\" cannot be driven as one connected path: at wp_idx {} ({:.2f}, {:.2f}) it leaves lane \"{}\", "
          "which leads nowhere ({:.2f} m past its end)",
          route.id, i, p.x(), p.y(), lanes_[static_cast<std::size_t>(lane)].id, place_on_lane(lane, p).distance));
    LanePlace place = place_on_lane(lane, p);
    int visit = static_cast<int>(rl.lanes.size()) - 1;
    // Short of the lane's start, off it: a route drawn with a 180-degree spike across a lane's
    // end (the line overshoots into the junction and comes back, seed 137) lies back on a lane
    // it has driven; that waypoint is placed there (the walk goes on from the current lane).
    if (place.distance > kOffLane && lanes_[static_cast<std::size_t>(lane)].shape.project(p).before_start) {
      for (int back = visit - 1; back >= std::max(0, visit - kMaxChain); --back) {
        const int earlier = rl.lanes[static_cast<std::size_t>(back)];
        const LanePlace there = place_on_lane(earlier, p);
        if (there.distance < place.distance && !lanes_[static_cast<std::size_t>(earlier)].shape.project(p).after_end) {
          place = there;
          visit = back;
        }
      }
    }
    rl.points.push_back(place);
    rl.visits.push_back(visit);
  }
  return rl;
}

}  // namespace orch
