#include "map/junction_path_fit.hpp"

#include <algorithm>

namespace orch {

namespace {

// The largest distance of passage jp's waypoints from the path of passage `other` through
// the same zone (the other route's own points there: its connection).
double farthest_from_path(const WaypointFile& wf, const JunctionPassage& jp, const JunctionPassage& other) {
  const WaypointRoute& route = wf.routes[jp.route];
  const WaypointRoute& along = wf.routes[other.route];
  const WaypointRoute path = make_line(along.id, stretch(along, other.s0, other.s1));
  double worst = 0;
  for (std::size_t i = 0; i < route.points.size(); ++i) {
    const double s = route.line.s_at_index(i);
    if (s >= jp.s0 && s <= jp.s1) worst = std::max(worst, path.line.project(route.line.point(i)).distance);
  }
  return worst;
}

}  // namespace

double farthest_on(const WaypointRoute& route, const JunctionPassage& jp, const Polyline& l, bool at_end) {
  double worst = 0;
  for (std::size_t i = 0; i < route.points.size(); ++i) {
    const double s = route.line.s_at_index(i);
    if (s < jp.s0 || s > jp.s1) continue;
    const Polyline::Projection pr = l.project(route.line.point(i));
    if (at_end ? !pr.before_start : !pr.after_end) worst = std::max(worst, pr.distance);
  }
  return worst;
}

bool fits_a_path_on(const WaypointFile& wf, const std::vector<JunctionPassage>& passages, const JunctionPassage& jp,
                    int k, bool loose_end) {
  for (const JunctionPassage& other : passages) {
    if (&other == &jp || other.zone != jp.zone ||
        !(loose_end ? other.before == k && other.after >= 0 : other.after == k && other.before >= 0))
      continue;
    if (farthest_from_path(wf, jp, other) <= kLaneFit) return true;
  }
  return false;
}

bool fits_a_path_between(const WaypointFile& wf, const std::vector<JunctionPassage>& passages,
                         const JunctionPassage& jp, int from, int to) {
  bool any = false;
  for (const JunctionPassage& other : passages) {
    if (&other == &jp || other.zone != jp.zone || other.before != from || other.after != to) continue;
    any = true;
    if (farthest_from_path(wf, jp, other) <= kLaneFit) return true;
  }
  return !any;
}

}  // namespace orch
