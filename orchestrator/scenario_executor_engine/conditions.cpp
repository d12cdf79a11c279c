#include "scenario_executor_engine/conditions.hpp"

#include "map/position_resolver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace orch::engine {

using namespace orch::scenario;

namespace {

constexpr double kTolerance = 1e-9;

const ActorState* present(const WorldSnapshot& snap, ActorId id) {
  const ActorState* a = snap.find(id);
  return (a && a->present) ? a : nullptr;
}

// Along-road measures count in the actor's direction of travel.
int direction(const ConditionContext& ctx, ActorId id) { return ctx.direction_of ? ctx.direction_of(id) : 1; }

double half_length(const ActorTable& actors, ActorId id) {
  const ActorSlot* s = actors.find(id);
  return s ? s->model.length / 2 : 0.0;
}

Vec2 waypoint_point(const WaypointFile& wps, const WaypointRef& ref) {  // past the end: the last point
  const position::RoutePlace place = position::PositionResolver(wps).place(ref);
  return place.route->line.point_at(place.s);
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double f = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + f * d)).norm();
}

// Distance measure with the format's sign rule for negative values.
bool compare_signed_gap(double gap, const double* gap_before, Comparison c, double value) {
  if (value >= 0) {
    if (gap < 0) return false;
    return compare_measure(gap, gap_before, c, value);
  }
  if (gap > 0) return false;
  const double before_abs = gap_before ? std::abs(*gap_before) : 0.0;
  return compare_measure(std::abs(gap), gap_before ? &before_abs : nullptr, c, std::abs(value));
}

ConditionOutcome outcome(const PositionCondition& c, const ConditionContext& ctx) {
  const ActorState* now = present(ctx.now, c.actor);
  if (!now) return {false, {}};
  const Vec2 target = waypoint_point(ctx.waypoints, c.waypoint);
  const ActorState* before = ctx.before ? present(*ctx.before, c.actor) : nullptr;
  const Vec2 from = before ? before->position : now->position;
  const double d = point_segment_distance(target, from, now->position);
  const bool holds = d <= c.tolerance + kTolerance;
  if (!holds) return {false, {}};
  return {true, fmt::format("actor {} reached {}[{}] ({:.2f} m <= {} m)", c.actor, c.waypoint.wp_id,
                            c.waypoint.wp_idx, d, c.tolerance)};
}

double speed_measure(const SpeedCondition& c, const WorldSnapshot& snap, bool* ok) {
  const ActorState* a = present(snap, c.actor);
  if (!a) return *ok = false, 0.0;
  if (c.type == SpeedType::Absolute) return a->speed;
  const ActorState* t = present(snap, c.target.value_or(0));
  if (!t) return *ok = false, 0.0;
  return a->speed - t->speed;
}

ConditionOutcome outcome(const SpeedCondition& c, const ConditionContext& ctx) {
  bool ok = true;
  const double v = speed_measure(c, ctx.now, &ok);
  if (!ok) return {false, {}};
  bool ok_before = ctx.before != nullptr;
  const double vb = ok_before ? speed_measure(c, *ctx.before, &ok_before) : 0.0;
  const bool holds = compare_measure(v, ok_before ? &vb : nullptr, c.comparison, c.value);
  if (!holds) return {false, {}};
  const char* what = c.type == SpeedType::Absolute ? "speed" : "relative speed";
  return {true, fmt::format("{} of actor {} {:.2f} km/h {} {:.2f}", what, c.actor, v * 3.6,
                             to_string(c.comparison), c.value * 3.6)};
}

std::optional<double> distance_measure(const DistanceCondition& c, const WorldSnapshot& snap,
                                       const ConditionContext& ctx) {
  const ActorState* a = present(snap, c.actor);
  const ActorState* t = present(snap, c.target);
  if (!a || !t) return std::nullopt;
  double gap;
  if (c.type == DistanceType::Straight) {
    const Vec2 rel = t->position - a->position;
    const Vec2 facing(std::cos(a->heading), std::sin(a->heading));
    gap = rel.dot(facing) >= 0 ? rel.norm() : -rel.norm();
  } else {
    const WaypointRoute* route = ctx.route_of(c.actor);
    if (!route) return std::nullopt;
    // A target on a route that crosses or joins the actor's: measured through the conflict point.
    const WaypointRoute* other = ctx.route_of(c.target);
    std::optional<double> through_conflict;
    if (other && ctx.meetings) through_conflict = conflict_point_gap(*route, a->position, *other, t->position, *ctx.meetings);
    gap = through_conflict ? *through_conflict : direction(ctx, c.actor) * along_road(*route, a->position, t->position);
  }
  if (c.measure == MeasureType::Surface) {
    const double halves = half_length(ctx.actors, c.actor) + half_length(ctx.actors, c.target);
    gap = gap >= 0 ? std::max(0.0, gap - halves) : std::min(0.0, gap + halves);
  }
  return gap;
}

ConditionOutcome outcome(const DistanceCondition& c, const ConditionContext& ctx) {
  const auto gap = distance_measure(c, ctx.now, ctx);
  if (!gap) return {false, {}};
  const auto before = ctx.before ? distance_measure(c, *ctx.before, ctx) : std::nullopt;
  const bool holds = compare_signed_gap(*gap, before ? &*before : nullptr, c.comparison, c.value);
  if (!holds) return {false, {}};
  return {true, fmt::format("{} distance actor {} -> {} {:.2f} m {} {}",
                             c.type == DistanceType::Straight ? "straight" : "traveled", c.actor, c.target, *gap,
                             to_string(c.comparison), c.value)};
}

// Seconds until the actor's front reaches the waypoint at its current speed; +inf when it
// stands still, nullopt once it has passed the waypoint (it will not arrive).
std::optional<double> headway(const TimeHeadwayCondition& c, const WorldSnapshot& snap,
                              const ConditionContext& ctx) {
  const ActorState* a = present(snap, c.actor);
  const WaypointRoute* route = ctx.route_of(c.actor);
  if (!a || !route) return std::nullopt;
  const double gap = direction(ctx, c.actor) * along_road(*route, a->position, waypoint_point(ctx.waypoints, c.waypoint)) -
                     half_length(ctx.actors, c.actor);
  if (gap < 0) return std::nullopt;
  if (a->speed <= 1e-6) return std::numeric_limits<double>::infinity();
  return gap / a->speed;
}

ConditionOutcome outcome(const TimeHeadwayCondition& c, const ConditionContext& ctx) {
  const auto h = headway(c, ctx.now, ctx);
  if (!h) return {false, {}};
  const auto hb = ctx.before ? headway(c, *ctx.before, ctx) : std::nullopt;
  const bool usable_before = hb && std::isfinite(*hb) && std::isfinite(*h);
  const bool holds = compare_measure(*h, usable_before ? &*hb : nullptr, c.comparison, c.value);
  if (!holds) return {false, {}};
  return {true, fmt::format("time headway of actor {} to {}[{}] {:.2f} s {} {}", c.actor, c.waypoint.wp_id,
                             c.waypoint.wp_idx, *h, to_string(c.comparison), c.value)};
}

ConditionOutcome outcome(const CollisionCondition& c, const ConditionContext& ctx) {
  if (c.target) {
    const bool hit = ctx.collided_with && ctx.collided_with(c.actor, *c.target);
    if (!hit) return {false, {}};
    return {true, fmt::format("actor {} collided with actor {}", c.actor, *c.target)};
  }
  const bool hit = ctx.collided && ctx.collided(c.actor);
  if (!hit) return {false, {}};
  return {true, fmt::format("actor {} collided", c.actor)};
}

ConditionOutcome outcome(const SimulationTimeCondition& c, const ConditionContext& ctx) {
  const double before = ctx.before ? ctx.before->time : 0.0;
  const bool holds = compare_measure(ctx.now.time, ctx.before ? &before : nullptr, c.comparison, c.value);
  if (!holds) return {false, {}};
  return {true, fmt::format("simulation time {:.2f} s {} {}", ctx.now.time, to_string(c.comparison), c.value)};
}

}  // namespace

bool compare_measure(double now, const double* before, Comparison c, double value) {
  switch (c) {
    case Comparison::Greater: return now > value + kTolerance;
    case Comparison::GreaterEqual: return now >= value - kTolerance;
    case Comparison::Less: return now < value - kTolerance;
    case Comparison::LessEqual: return now <= value + kTolerance;
    case Comparison::Equal:
      if (std::abs(now - value) <= 1e-6) return true;
      return before && ((*before < value && now > value) || (*before > value && now < value));
  }
  return false;
}

double along_road(const WaypointRoute& route, const Vec2& from, const Vec2& to) {
  const auto a = route.line.project(from);
  const auto b = route.line.project(to);
  // Beyond the route's ends, continue straight along the end direction.
  auto extended = [&](const Polyline::Projection& p, const Vec2& pt) {
    if (!p.before_start && !p.after_end) return p.s;
    return p.s + (pt - route.line.point_at(p.s)).dot(route.line.tangent_at(p.s));
  };
  return extended(b, to) - extended(a, from);
}

ConditionOutcome evaluate(const Condition& c, const ConditionContext& ctx) {
  // One `outcome` overload per condition type (scenario/elements.hpp): a type without one
  // does not compile.
  return std::visit([&](const auto& k) { return outcome(k, ctx); }, c.kind);
}

bool evaluate(const ConditionGroup& g, const ConditionContext& ctx, std::vector<std::string>* fired) {
  if (g.items.empty()) return true;
  std::vector<std::string> details;
  bool any = false;
  bool all = true;
  for (const auto& item : g.items) {
    bool holds;
    if (const auto* c = std::get_if<Condition>(&item.node)) {
      ConditionOutcome o = evaluate(*c, ctx);
      holds = o.holds;
      if (holds) details.push_back(std::move(o.detail));
    } else {
      holds = evaluate(std::get<ConditionGroup>(item.node), ctx, &details);
    }
    any = any || holds;
    all = all && holds;
    // No short-circuit: every condition sees every step, so crossing detection ("=")
    // and the details stay complete.
  }
  const bool result = g.logic == Logic::And ? all : any;
  if (result && fired) fired->insert(fired->end(), details.begin(), details.end());
  return result;
}

}  // namespace orch::engine
