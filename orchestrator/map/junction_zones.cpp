#include "map/junction_zones.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "core/checked_numeric.hpp"
#include "core/components.hpp"

namespace orch {

namespace {

constexpr double kTangentChord = 1.5;          // m each side: tangents over 3 m ignore drawing noise
constexpr double kSameLaneCos = 0.9659;        // cos 15 deg
constexpr double kNeighbourCos = 0.9848;       // cos 10 deg: neighbouring lanes run parallel
constexpr double kMinNeighbourSpacing = 2.0;   // m (route_corridors.hpp: kMinLaneSpacing)
constexpr double kMaxNeighbourSpacing = 6.0;   // m (route_corridors.hpp: kMaxLaneSpacing)
constexpr double kCell = 6.0;                  // m, grid cell >= every query radius
constexpr double kProbe = 0.5;                 // m before an entry / after an exit
constexpr int kMaxAlignRounds = 20;
constexpr double kMinEndPiece = 1.0;            // m: a shorter end of a route stays in its junction
constexpr double kMaxReturnGap = 30.0;         // m: a shorter stretch from a junction back to it joins it

struct SegmentRef {
  std::size_t route;
  std::size_t segment;
};

// Every route segment, bucketed by grid cell, so "which routes pass within r of p" is cheap.
class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<WaypointRoute>& routes) : routes_(routes) {
    for (std::size_t r = 0; r < routes.size(); ++r) {
      const auto& pts = routes[r].line.points();
      for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Vec2 lo = pts[i].cwiseMin(pts[i + 1]);
        const Vec2 hi = pts[i].cwiseMax(pts[i + 1]);
        for (long long cx = cell(lo.x()); cx <= cell(hi.x()); ++cx)
          for (long long cy = cell(lo.y()); cy <= cell(hi.y()); ++cy) cells_[key(cx, cy)].push_back({r, i});
      }
    }
  }

  // The nearest point of each separate stretch of every route passing within `radius` of p.
  struct Near {
    std::size_t route;
    double s;         // arc length of the foot on that route
    double distance;
  };
  [[nodiscard]] std::vector<Near> near(const Vec2& p, double radius) const {
    std::map<std::size_t, std::vector<std::pair<std::size_t, double>>> by_route;  // segment, distance
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cell(p.x()) + dx, cell(p.y()) + dy));
        if (it == cells_.end()) continue;
        for (const SegmentRef& ref : it->second) {
          const double d = segment_distance(ref, p);
          if (d <= radius) by_route[ref.route].emplace_back(ref.segment, d);
        }
      }
    std::vector<Near> out;
    for (auto& [route, segs] : by_route) {
      std::sort(segs.begin(), segs.end());
      segs.erase(std::unique(segs.begin(), segs.end()), segs.end());
      // Runs of consecutive segments are one stretch; keep each run's nearest segment. A
      // foot on the route's very first or last point is where the route ends, not a place
      // beside p (and on a closed route the stretch goes on at the other end).
      const double length = routes_[route].line.length();
      for (std::size_t a = 0; a < segs.size();) {
        std::size_t b = a;
        std::size_t best = a;
        while (b + 1 < segs.size() && segs[b + 1].first <= segs[b].first + 2) {
          ++b;
          if (segs[b].second < segs[best].second) best = b;
        }
        const double s = foot_s({route, segs[best].first}, p);
        if (s > 1e-6 && s < length - 1e-6) out.push_back({route, s, segs[best].second});
        a = b + 1;
      }
    }
    return out;
  }

 private:
  static long long cell(double v) { return grid_cell(v, kCell); }
  static long long key(long long cx, long long cy) { return cx * 4000037LL + cy; }
  [[nodiscard]] double segment_f(const SegmentRef& ref, const Vec2& p) const {
    const Vec2& a = routes_[ref.route].line.point(ref.segment);
    const Vec2 d = routes_[ref.route].line.point(ref.segment + 1) - a;
    const double len2 = d.squaredNorm();
    return len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  }
  [[nodiscard]] double segment_distance(const SegmentRef& ref, const Vec2& p) const {
    const Vec2& a = routes_[ref.route].line.point(ref.segment);
    const Vec2& b = routes_[ref.route].line.point(ref.segment + 1);
    return (p - (a + segment_f(ref, p) * (b - a))).norm();
  }
  [[nodiscard]] double foot_s(const SegmentRef& ref, const Vec2& p) const {
    const Polyline& line = routes_[ref.route].line;
    const double s0 = line.s_at_index(ref.segment);
    return s0 + segment_f(ref, p) * (line.s_at_index(ref.segment + 1) - s0);
  }

  const std::vector<WaypointRoute>& routes_;
  std::unordered_map<long long, std::vector<SegmentRef>> cells_;
};

Vec2 tangent(const WaypointRoute& r, double s) {
  const Vec2 d = r.line.point_at(s + kTangentChord) - r.line.point_at(s - kTangentChord);
  return d.norm() > 1e-9 ? Vec2(d.normalized()) : r.line.tangent_at(s);
}

// Arc-length distance between two places on one route (around the loop for closed routes).
double arc_gap(const WaypointRoute& r, double a, double b) {
  const double d = std::abs(a - b);
  return is_closed_route(r) ? std::min(d, r.line.length() - d) : d;
}

enum class Relation { Same, Neighbour, Conflict, Apart };

Relation relate(const WaypointRoute& r, double s, const WaypointRoute& q, double sq, double distance) {
  const double c = tangent(r, s).dot(tangent(q, sq));
  if (distance < kSameLaneDistance && c > kSameLaneCos) return Relation::Same;
  if (std::abs(c) > kNeighbourCos && distance >= kMinNeighbourSpacing)
    return distance <= kMaxNeighbourSpacing && c > 0 ? Relation::Neighbour : Relation::Apart;
  return distance < kConflictReach ? Relation::Conflict : Relation::Apart;
}


struct Interval {
  double s0;
  double s1;
  std::size_t id;  // in Components
};

class ZoneFinder {
 public:
  explicit ZoneFinder(const WaypointFile& wf) : routes_(wf.routes), grid_(wf.routes), intervals_(routes_.size()) {}

  JunctionZones run() {
    find_conflicts();
    for (std::size_t r = 0; r < routes_.size(); ++r) normalise(r);
    add_spread_conflicts();
    link_conflicts();
    split_loops();
    for (int round = 0; round < kMaxAlignRounds && align_round(); ++round) {
    }
    return result();
  }

 private:
  void find_conflicts() {
    for (std::size_t r = 0; r < routes_.size(); ++r) {
      const WaypointRoute& route = routes_[r];
      for (std::size_t i = 0; i < route.points.size(); ++i) {
        const double s = route.line.s_at_index(i);
        const Vec2& p = route.line.point(i);
        for (const auto& n : grid_.near(p, kConflictReach)) {
          if (n.route == r && arc_gap(route, s, n.s) < 3 * kConflictReach) continue;  // itself, here
          const Relation rel = relate(route, s, routes_[n.route], n.s, n.distance);
          if (rel == Relation::Same && n.distance > kMaxSameLaneSpread) spread_.push_back({r, s, n.route, n.s});
          if (rel != Relation::Conflict) continue;
          conflicts_.push_back({r, s, n.route, n.s});
          add_interval(r, s - kZoneMargin, s + kZoneMargin);
          add_interval(n.route, n.s - kZoneMargin, n.s + kZoneMargin);
        }
      }
    }
  }

  // Routes drawn along one lane, but farther apart than one lane holds within the fit
  // tolerance (kMaxSameLaneSpread: two routes' turns drawn with radii a little apart, a
  // route drifting 0.2 m off its neighbour on the shared lane) need paths of their own
  // there: a junction, in which the second one gets a detour lane (junction_detours.hpp).
  // Only where neither route is in a junction yet: inside one, each route's path is its own
  // connection already (and a detour lane where it shares its pair of lanes). Also at a
  // route's own start or end (seed 278: a route starting 0.22 m beside another's lane lay
  // 0.11 m off their best fit): it starts (ends) inside that junction, on a lane of its own
  // there (junction_pieces.cpp; seed 107, 0.18 m beside another's last metres, left out of
  // the junction before that, builds either way; seed 166 ends 1.9 m after one).
  void add_spread_conflicts() {
    std::vector<std::size_t> touched;
    for (const Conflict& c : spread_) {
      if (containing(c.r, c.s) || containing(c.q, c.sq)) continue;
      conflicts_.push_back(c);
      add_interval(c.r, c.s - kZoneMargin, c.s + kZoneMargin);
      add_interval(c.q, c.sq - kZoneMargin, c.sq + kZoneMargin);
      touched.push_back(c.r);
      touched.push_back(c.q);
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (const std::size_t r : touched) normalise(r);
  }

  void add_interval(std::size_t r, double s0, double s1) { intervals_[r].push_back({s0, s1, comp_.add()}); }

  // Sort, clamp and merge a route's intervals (gaps shorter than kMinPieceLength close);
  // merged intervals join their components. On a closed route intervals are kept with s0 in
  // [0, length) and may reach past length (across the closing point); the last one swallows
  // the first when the gap across the closing point is short.
  void normalise(std::size_t r) {
    auto& iv = intervals_[r];
    if (iv.empty()) return;
    const WaypointRoute& route = routes_[r];
    const double length = route.line.length();
    const bool closed = is_closed_route(route);
    for (auto& x : iv) {
      if (closed) {
        const double shift = std::floor(x.s0 / length) * length;
        x.s0 -= shift;
        x.s1 -= shift;
      } else {
        x.s0 = std::max(0.0, x.s0);
        x.s1 = std::min(x.s1, length);
      }
    }
    std::sort(iv.begin(), iv.end(), [](const Interval& a, const Interval& b) { return a.s0 < b.s0; });
    std::vector<Interval> merged;
    for (const Interval& x : iv) {
      if (!merged.empty() && x.s0 <= merged.back().s1 + kMinPieceLength) {
        merged.back().s1 = std::max(merged.back().s1, x.s1);
        comp_.join(merged.back().id, x.id);
      } else {
        merged.push_back(x);
      }
    }
    if (closed) {
      while (merged.size() > 1 && merged.back().s1 + kMinPieceLength >= merged.front().s0 + length) {
        merged.back().s1 = std::max(merged.back().s1, merged.front().s1 + length);
        comp_.join(merged.back().id, merged.front().id);
        merged.erase(merged.begin());
      }
      // A passage that covers the whole loop leaves no piece: keep one, the loop's length.
      if (merged.size() == 1 && merged.front().s1 - merged.front().s0 >= length - kMinPieceLength)
        merged.front().s1 = merged.front().s0 + length - kMinPieceLength;
    } else {
      // Near the route's own ends a leftover shorter than kMinEndPiece would be a stub: the
      // passage reaches the end. A longer one stays a lane of its own (a dead end, or folded
      // into the lane it is drawn along), so the route's last waypoints lie on a lane.
      if (merged.front().s0 < kMinEndPiece) merged.front().s0 = 0;
      if (merged.back().s1 > length - kMinEndPiece) merged.back().s1 = length;
    }
    iv = std::move(merged);
  }

  // A closed route needs at least two junctions on it (one edge cannot lead from a node back
  // to itself): plain ones, where nothing else meets it, at the middle of its longest pieces.
  void split_loops() {
    for (std::size_t r = 0; r < routes_.size(); ++r) {
      const WaypointRoute& route = routes_[r];
      if (!is_closed_route(route)) continue;
      const double length = route.line.length();
      while (intervals_[r].size() < 2) {
        double at = length / 4;
        if (!intervals_[r].empty()) {
          const Interval& x = intervals_[r].front();
          at = std::fmod((x.s1 + x.s0 + length) / 2, length);
        }
        add_interval(r, at - kProbe, at + kProbe);
        normalise(r);
      }
    }
  }

  // The interval of route r containing arc length s (wrap-aware), or nullptr.
  Interval* containing(std::size_t r, double s) {
    const double length = routes_[r].line.length();
    for (Interval& x : intervals_[r]) {
      if (s >= x.s0 - 1e-6 && s <= x.s1 + 1e-6) return &x;
      if (x.s1 > length && s + length >= x.s0 - 1e-6 && s + length <= x.s1 + 1e-6) return &x;
    }
    return nullptr;
  }

  void link_conflicts() {
    for (const auto& c : conflicts_) {
      Interval* a = containing(c.r, c.s);
      Interval* b = containing(c.q, c.sq);
      if (a && b) comp_.join(a->id, b->id);
    }
  }

  // One round of making passage ends consistent: where a route enters (leaves) a junction,
  // every route on the same lane or on a neighbouring lane of the same road enters (leaves)
  // it at the foot of that point, so that all lanes of an edge end at one junction.
  bool align_round() {
    bool changed = false;
    for (std::size_t r = 0; r < routes_.size(); ++r) {
      const WaypointRoute& route = routes_[r];
      const double length = route.line.length();
      const std::vector<Interval> snapshot = intervals_[r];
      for (const Interval& x : snapshot) {
        for (const bool entry : {true, false}) {
          const double edge_s = entry ? x.s0 : x.s1;
          if ((entry && edge_s <= 0) || (!entry && edge_s >= length && !is_closed_route(route))) continue;
          const double probe_s = entry ? edge_s - kProbe : edge_s + kProbe;
          const Vec2 probe = route.line.point_at(wrap(route, probe_s));
          const Vec2 edge_point = route.line.point_at(wrap(route, edge_s));
          for (const auto& n : grid_.near(probe, kMaxNeighbourSpacing)) {
            if (n.route == r && arc_gap(route, wrap(route, probe_s), n.s) < 3 * kConflictReach) continue;
            const WaypointRoute& q = routes_[n.route];
            const Relation rel = relate(route, wrap(route, probe_s), q, n.s, n.distance);
            if (rel != Relation::Same && rel != Relation::Neighbour) continue;
            const double foot = q.line.project_near(edge_point, n.s, 3 * kProbe + 2).s;
            changed = require(n.route, foot, entry, x.id, x.s1 - x.s0) || changed;
          }
        }
      }
      normalise(r);  // the other routes were normalised where require() changed them
    }
    return changed;
  }

  // Route q must have a passage starting (entry) or ending (exit) at `foot`, in the
  // component `id`. Returns whether anything changed.
  bool require(std::size_t q, double foot, bool entry, std::size_t id, double length_hint) {
    if (Interval* x = containing(q, foot)) {
      const bool moves = entry ? foot < x->s0 - 1e-3 : foot > x->s1 + 1e-3;
      const bool joins = comp_.root(x->id) != comp_.root(id);
      if (entry) x->s0 = std::min(x->s0, foot);
      else x->s1 = std::max(x->s1, foot);
      comp_.join(x->id, id);
      return moves || joins;
    }
    // A lane that only passes the junction (beside a turning one) needs a short passage; its
    // other end is aligned with its own neighbours in the next round.
    const double len = std::min(kMinPieceLength, std::max(length_hint, 1.0));
    if (entry) add_interval(q, foot, foot + len);
    else add_interval(q, foot - len, foot);
    comp_.join(intervals_[q].back().id, id);
    normalise(q);
    return true;
  }

  [[nodiscard]] double wrap(const WaypointRoute& r, double s) const {
    if (!is_closed_route(r)) return s;
    const double length = r.line.length();
    return std::fmod(std::fmod(s, length) + length, length);
  }

  // A short stretch between two passages of one zone would become a lane from a junction
  // back to itself, inside the junction's own shape (netconvert cuts it to nothing): the
  // stretch joins the junction instead.
  void absorb_returns() {
    for (std::size_t r = 0; r < routes_.size(); ++r) {
      auto& iv = intervals_[r];
      std::vector<Interval> merged;
      for (const Interval& x : iv) {
        if (!merged.empty() && comp_.root(merged.back().id) == comp_.root(x.id) &&
            x.s0 - merged.back().s1 < kMaxReturnGap) {
          merged.back().s1 = std::max(merged.back().s1, x.s1);
          continue;
        }
        merged.push_back(x);
      }
      iv = std::move(merged);
    }
  }

  JunctionZones result() {
    absorb_returns();
    JunctionZones out;
    out.passages.resize(routes_.size());
    std::map<std::size_t, int> zone_of_root;
    for (std::size_t r = 0; r < routes_.size(); ++r)
      for (const Interval& x : intervals_[r]) {
        const auto [it, fresh] = zone_of_root.emplace(comp_.root(x.id), out.count);
        if (fresh) ++out.count;
        out.passages[r].push_back({x.s0, x.s1, it->second});
      }
    return out;
  }

  struct Conflict {
    std::size_t r;
    double s;
    std::size_t q;
    double sq;
  };

  const std::vector<WaypointRoute>& routes_;
  SegmentGrid grid_;
  std::vector<std::vector<Interval>> intervals_;
  std::vector<Conflict> conflicts_;
  std::vector<Conflict> spread_;  // on one lane but farther apart than one lane holds
  Components comp_;
};

}  // namespace

bool is_closed_route(const WaypointRoute& route) {
  return route.line.size() > 2 && (route.line.points().back() - route.line.point(0)).norm() < 0.5 &&
         route.line.length() > 4 * kConflictReach;
}

JunctionZones find_junction_zones(const WaypointFile& waypoints) { return ZoneFinder(waypoints).run(); }

}  // namespace orch
