#include "map/route_corridors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/checked_numeric.hpp"
#include "core/components.hpp"

namespace orch {

namespace {

constexpr double kSampleStep = 2.0;  // m between the samples that compare two routes

// Which samples of a route lie within a radius of a point. Polyline::project falls back
// to scanning every segment when the point is far from the line, which for thousands of
// samples of an unrelated route costs seconds; this hash answers "is it near at all" first.
class NearIndex {
 public:
  explicit NearIndex(const Polyline& line) {
    for (double s = 0;; s += kSampleStep) {
      const double at = std::min(s, line.length());
      const Vec2 p = line.point_at(at);
      cells_[key(cell_of(p.x()), cell_of(p.y()))].push_back(p);
      if (at >= line.length()) break;
    }
  }
  // Radius must not exceed kCell; samples are kSampleStep apart, so a line passing within
  // `radius` has a sample within radius + kSampleStep / 2.
  [[nodiscard]] bool near(const Vec2& p, double radius) const {
    const double r = radius + kSampleStep / 2;
    const long long cx = cell_of(p.x());
    const long long cy = cell_of(p.y());
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const Vec2& q : it->second)
          if ((q - p).squaredNorm() <= r * r) return true;
      }
    return false;
  }

 private:
  static constexpr double kCell = 10.0;
  static long long cell_of(double v) { return grid_cell(v, kCell); }
  static long long key(long long cx, long long cy) { return cx * 2000003LL + cy; }
  std::unordered_map<long long, std::vector<Vec2>> cells_;
};

RouteRelation relate_lines(const Polyline& a, const Polyline& b, const NearIndex& b_index) {
  // Samples of `a` beside `b` in the same direction: (arc length on a, lateral offset).
  std::vector<std::pair<double, double>> beside;
  std::size_t samples = 0;
  std::size_t first_beside = 0;
  std::size_t last_beside = 0;
  const double reach = kMaxLaneSpacing + kMaxSpacingVariation;
  for (double s = 0;; s += kSampleStep) {
    const double at = std::min(s, a.length());
    const Vec2 p = a.point_at(at);
    ++samples;
    if (b_index.near(p, reach)) {
      const Polyline::Projection proj = b.project(p);
      const bool inside = !proj.before_start && !proj.after_end;
      const bool same_direction = a.tangent_at(at).dot(b.tangent_at(proj.s)) >= kSameDirectionCos;
      if (inside && same_direction && proj.distance <= reach) {
        if (beside.empty()) first_beside = samples - 1;
        last_beside = samples - 1;
        beside.emplace_back(at, proj.lateral);
      }
    }
    if (at >= a.length()) break;
  }
  RouteRelation rel;
  if (beside.empty()) return rel;
  rel.overlap = beside.back().first - beside.front().first;
  // A route that crosses, or runs beside b only now and then, is not a neighbouring lane.
  const auto span = static_cast<double>(last_beside - first_beside + 1);
  if (static_cast<double>(beside.size()) < 0.9 * span) return rel;

  std::vector<double> laterals;
  laterals.reserve(beside.size());
  for (const auto& [s, lat] : beside) laterals.push_back(lat);
  const auto [lo, hi] = std::minmax_element(laterals.begin(), laterals.end());
  // A lane that drifts away (a branching exit, a merge taper) is not "parallel": its
  // spacing would have to change along one edge.
  if (*hi - *lo > kMaxSpacingVariation) return rel;
  std::nth_element(laterals.begin(), laterals.begin() + static_cast<long>(laterals.size() / 2), laterals.end());
  rel.lateral = laterals[laterals.size() / 2];
  // Any real stretch on the same lane counts (two lanes cannot be stacked even briefly);
  // neighbouring lanes need a substantial overlap to be trusted, and never less than a car
  // length: a stub of a metre or two (a route's start inside a junction, cut off as a dead
  // end of its own) is no lane of the road it happens to lie beside.
  const double needed =
      std::max(kMinParallelStub, std::min(kMinParallelOverlap, 0.5 * std::min(a.length(), b.length())));
  if (std::abs(rel.lateral) < kMinLaneSpacing) {
    if (rel.overlap >= kMinCoincidentOverlap) rel.kind = RouteRelation::Kind::Coincident;
  } else if (std::abs(rel.lateral) <= kMaxLaneSpacing && rel.overlap >= needed) {
    rel.kind = RouteRelation::Kind::Parallel;
  }
  return rel;
}

struct PairRelation {
  std::size_t a = 0;
  std::size_t b = 0;
  RouteRelation rel;
};


}  // namespace

RouteRelation relate_routes(const Polyline& a, const Polyline& b) { return relate_lines(a, b, NearIndex(b)); }

std::vector<std::vector<std::size_t>> find_corridors(const WaypointFile& waypoints, std::vector<std::string>& notes,
                                                     const std::vector<bool>& solitary) {
  const auto& routes = waypoints.routes;
  const std::size_t n = routes.size();
  std::vector<NearIndex> indices;
  indices.reserve(n);
  for (const auto& r : routes) indices.emplace_back(r.line);

  // Judge each pair from the shorter route: its points are the ones that lie beside the
  // other one (a lane that starts later lies wholly beside the longer lane).
  std::vector<PairRelation> parallel;
  std::vector<PairRelation> coincident;
  const auto alone = [&](std::size_t i) { return i < solitary.size() && solitary[i]; };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (alone(i) || alone(j)) continue;
      const bool i_shorter = routes[i].line.length() <= routes[j].line.length();
      const std::size_t a = i_shorter ? i : j;
      const std::size_t b = i_shorter ? j : i;
      const RouteRelation rel = relate_lines(routes[a].line, routes[b].line, indices[b]);
      if (rel.kind == RouteRelation::Kind::Parallel) parallel.push_back({i, j, rel});
      if (rel.kind == RouteRelation::Kind::Coincident) coincident.push_back({i, j, rel});
    }

  // Strongest evidence first, so that a doubtful pair cannot pull a route away from the
  // corridor it clearly belongs to.
  std::stable_sort(parallel.begin(), parallel.end(),
                   [](const PairRelation& x, const PairRelation& y) { return x.rel.overlap > y.rel.overlap; });
  Components comp(n);
  std::vector<std::string> refused;
  for (const PairRelation& p : parallel) {
    const std::size_t ra = comp.root(p.a);
    const std::size_t rb = comp.root(p.b);
    if (ra == rb) continue;
    const auto clash = std::find_if(coincident.begin(), coincident.end(), [&](const PairRelation& c) {
      const std::size_t ca = comp.root(c.a);
      const std::size_t cb = comp.root(c.b);
      return (ca == ra && cb == rb) || (ca == rb && cb == ra);
    });
    if (clash != coincident.end()) {
      refused.push_back(fmt::format("routes \"{}\" and \"{}\" look like neighbouring lanes, but joining them would "
                                    "put the coincident routes \"{}\" and \"{}\" into one road; kept apart",
                                    routes[p.a].id, routes[p.b].id, routes[clash->a].id, routes[clash->b].id));
      continue;
    }
    comp.join(p.a, p.b);
  }
  for (const PairRelation& c : coincident)
    notes.push_back(fmt::format("routes \"{}\" and \"{}\" run along the same lane ({:.2f} m apart); each gets lanes "
                                "of its own, on top of each other, and vehicles on them do not see each other",
                                routes[c.a].id, routes[c.b].id, std::abs(c.rel.lateral)));
  notes.insert(notes.end(), refused.begin(), refused.end());

  std::vector<std::vector<std::size_t>> corridors;
  std::unordered_map<std::size_t, std::size_t> corridor_of_root;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = comp.root(i);
    auto [it, fresh] = corridor_of_root.emplace(r, corridors.size());
    if (fresh) corridors.emplace_back();
    corridors[it->second].push_back(i);
  }
  for (const auto& c : corridors)
    if (c.size() == 1)
      notes.push_back(fmt::format("route \"{}\" has no parallel route: it becomes a single-lane road", routes[c[0]].id));
  return corridors;
}

}  // namespace orch
