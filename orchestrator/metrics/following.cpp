#include "metrics/following.hpp"

#include <algorithm>
#include <cmath>

namespace orch::metrics {

Following following_measures(std::string other, double gap, double speed_behind, double speed_ahead) {
  Following f;
  f.other = std::move(other);
  f.gap = std::max(0.0, gap);
  f.rel_speed = speed_behind - speed_ahead;
  if (f.rel_speed > 0) {
    f.ttc = f.gap / f.rel_speed;
    if (f.gap > 0) f.drac = f.rel_speed * f.rel_speed / (2 * f.gap);
  }
  if (speed_behind > 0) f.thw = f.gap / speed_behind;
  return f;
}

namespace {

struct OnRoute {
  double s = 0;        // in the direction of travel of the measured actor
  double lateral = 0;  // + = left of the route as drawn
  double speed = 0;    // along the route, in the measured actor's direction
};

OnRoute place(const Polyline::Projection& p, const Polyline& route, const Body& b, int direction) {
  const double tangent = route.heading_at(p.s);
  return {p.s * direction, p.lateral, b.speed * std::cos(b.heading - tangent) * direction};
}

}  // namespace

Neighbours find_neighbours(const Polyline& route, const Body& self, const std::vector<Body>& others) {
  Neighbours n;
  if (route.empty()) return n;
  // Along the road is never shorter than straight: farther bodies cannot count.
  const auto candidate = [&](const Body& o) {
    return o.id != self.id && (o.centre - self.centre).squaredNorm() < kFollowingRange * kFollowingRange;
  };
  // Nobody near (an ego alone on its road): no need to place the actor on its route.
  if (std::none_of(others.begin(), others.end(), candidate)) return n;
  const Polyline::Projection own = route.project(self.centre);
  // Along the route as drawn, or against it (overtaking through the oncoming lane).
  const int direction = std::cos(self.heading - route.heading_at(own.s)) >= 0 ? 1 : -1;
  const OnRoute me = place(own, route, self, direction);
  double best_ahead = kFollowingRange, best_behind = kFollowingRange;
  for (const Body& o : others) {
    if (!candidate(o)) continue;
    // On the path means within the two half-widths of the actor's own offset from the route.
    const auto projected = route.project_within(o.centre, std::abs(own.lateral) + (self.width + o.width) / 2);
    if (!projected) continue;
    const OnRoute it = place(*projected, route, o, direction);
    if (std::abs(it.lateral - me.lateral) >= (self.width + o.width) / 2) continue;
    const double ds = it.s - me.s;
    const double gap = std::abs(ds) - (self.length + o.length) / 2;
    if (ds > 0 && ds < best_ahead) {
      best_ahead = ds;
      n.leader = following_measures(o.id, gap, me.speed, it.speed);
    } else if (ds <= 0 && -ds < best_behind) {
      best_behind = -ds;
      n.follower = following_measures(o.id, gap, it.speed, me.speed);
    }
  }
  return n;
}

}  // namespace orch::metrics
