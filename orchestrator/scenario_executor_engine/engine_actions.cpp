// Scene actions. Each actor has independent axes; a new action replaces the running one on
// its axis only (docs/scenario-format.md "Actions"):
//   longitudinal: speed, traveled_distance       lateral: lane_change, lane_offset,
//   route_move wp_offset                          route: route_move waypoint
//   lights: light_state (per light)               sound: sound_state
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "scenario_executor_engine/conditions.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "map/position_resolver.hpp"

namespace orch::engine {

using namespace orch::scenario;

namespace {

// Gap keeping for traveled_distance: follow the target's speed, closing the gap error at
// kGapGain per second, within kGapAccel. Plausible for a car (|a| <= 4 m/s^2).
constexpr double kGapGain = 0.5;   // 1/s
constexpr double kGapAccel = 4.0;  // m/s^2

std::string on_off(const std::optional<bool>& v) { return v ? (*v ? "on" : "off") : "unchanged"; }

std::string describe_speed(const SpeedAction& a) {
  std::string what = a.type == SpeedType::Absolute
                         ? fmt::format("{:.1f} km/h", a.value * 3.6)
                         : fmt::format("actor {} {:+.1f} km/h", a.target.value_or(0), a.value * 3.6);
  std::string how = a.accel.type == AccelType::Specify ? fmt::format("at {:g} m/s^2", a.accel.value) : "instantly";
  return fmt::format("speed: actor {} to {} {}", a.actor, what, how);
}

}  // namespace

void Engine::resolve_longitudinal(ActorId id, ScriptedMotion& m) {
  auto it = longitudinal_.find(id);
  if (it == longitudinal_.end()) return;
  if (const auto* hold = std::get_if<HoldSpeed>(&it->second)) {
    const SpeedAction& a = hold->action;
    double v = a.value;
    if (a.type == SpeedType::Relative) {
      const ActorState* target = current_.find(a.target.value_or(scenario_.ego.id));
      if (!target || !target->present) return;  // keep heading for the last target speed
      v += target->speed;
    }
    m.set_desired(std::max(0.0, v), a.accel.type == AccelType::Specify ? a.accel.value : 0.0);
    return;
  }
  if (std::holds_alternative<KeepSpeed>(it->second)) {
    m.set_desired(m.speed(), 0.0);
    return;
  }
  const auto& gap = std::get<KeepGap>(it->second).action;
  const ActorState* target = current_.find(gap.target);
  if (!target || !target->present) return;
  // + = the actor ahead of its target; through the conflict point when their routes only cross.
  double now_gap = m.direction() * along_road(m.route(), target->position, m.position());
  if (const WaypointRoute* other = route_of(gap.target))
    if (const auto g = conflict_point_gap(m.route(), m.position(), *other, target->position, meetings_)) now_gap = -*g;
  if (gap.measure == MeasureType::Surface) {
    const double halves = (actors_.find(id)->model.length + actors_.find(gap.target)->model.length) / 2;
    now_gap += now_gap >= 0 ? -halves : halves;
  }
  const double error = now_gap - gap.value;  // > 0: too far ahead of the wanted place
  m.set_desired(std::max(0.0, target->speed - kGapGain * error), kGapAccel);
}

void Engine::start_route_move(const RouteMoveAction& a, ScriptedMotion& m, double t, StepOutput& out) {
  auto event = [&](const std::string& text) { out.events.push_back({t, EventKind::Action, text}); };
  if (a.type == RouteMoveType::WpOffset) {
    std::vector<LateralLeg> legs;
    for (const auto& leg : a.legs) legs.push_back({leg.wp_offset.value_or(0.0), leg.time});
    event(fmt::format("route_move: actor {} through {} lateral offsets", a.actor, legs.size()));
    m.plan_lateral(legs, t);  // lateral axis only: the speed stays as it is
    return;
  }
  const bool pedestrian = actors_.find(a.actor)->tracked.kind == ActorKind::Pedestrian;
  std::vector<std::pair<Vec2, double>> walk;
  std::vector<RouteLegTarget> drive;
  for (const auto& leg : a.legs) {
    const position::RoutePlace place = position::PositionResolver(map_.waypoints).place(*leg.waypoint);
    const WaypointRoute* r = place.route;
    const double s = place.s;
    walk.emplace_back(r->line.offset_point(s, leg.wp_offset.value_or(0.0)), leg.time);
    drive.push_back({r, s, leg.wp_offset.value_or(0.0), leg.time});
  }
  event(fmt::format("route_move: actor {} through {} waypoint(s), {}", a.actor, a.legs.size(),
                    pedestrian ? "walking straight to each" : "along the road, arriving on time"));
  // The route axis owns position and speed until the last leg ends; then the actor keeps
  // the speed it arrived with.
  longitudinal_[a.actor] = KeepSpeed{};
  if (pedestrian) m.plan_walk(walk, t);
  else m.plan_route_legs(drive, t);
}

void Engine::start_action(const Action& action, double now, StepOutput& step_out) {
  // One action's behaviour per model type (scenario/elements.hpp): the overload set is the
  // dispatch, so an action type without a behaviour does not compile.
  struct Start {
    Engine& e;
    double t;
    StepOutput& out;

    void event(const std::string& text) const { out.events.push_back({t, EventKind::Action, text}); }
    bool require_present(ActorId id) const {
      const ActorState* a = e.current_.find(id);
      if (a && a->present) return true;
      e.fail(fmt::format("an action of this scene names actor {}, which is not in the simulation", id), t, out);
      return false;
    }
    ScriptedMotion* motion(ActorId id) const {
      auto it = e.motions_.find(id);
      return it == e.motions_.end() ? nullptr : &it->second;
    }
    void ego_only(ActorId id, const char* what) const {
      out.events.push_back({t, EventKind::Warning,
                            fmt::format("{} on actor {} ignored: the ego is driven by SUMO's driver model", what, id)});
    }

    void operator()(const SpeedAction& a) const {
      if (!require_present(a.actor)) return;
      event(describe_speed(a));
      if (ScriptedMotion* m = motion(a.actor)) {
        m->cancel_moves();  // a longitudinal action replaces a running route_move
        e.longitudinal_[a.actor] = HoldSpeed{a};
      } else if (a.type == SpeedType::Absolute) {
        if (!e.options_.external_ego) out.commands.push_back(SetMaxSpeed{"ego", a.value});
      } else {
        ego_only(a.actor, "a relative speed action");
      }
    }

    void operator()(const TraveledDistanceAction& a) const {
      if (!require_present(a.actor) || !require_present(a.target)) return;
      event(fmt::format("traveled_distance: actor {} keeps {:+.1f} m ({}) from actor {}", a.actor, a.value,
                        a.measure == MeasureType::Surface ? "surface" : "center", a.target));
      if (ScriptedMotion* m = motion(a.actor)) {
        m->cancel_moves();
        e.longitudinal_[a.actor] = KeepGap{a};
      } else {
        ego_only(a.actor, "traveled_distance");
      }
    }

    void operator()(const LaneChangeAction& a) const {
      if (!require_present(a.actor)) return;
      event(fmt::format("lane_change: actor {} to the lane of {} over {:g} s", a.actor, a.wp_id, a.time));
      ScriptedMotion* m = motion(a.actor);
      if (!m) return ego_only(a.actor, "lane_change");
      const WaypointRoute& target = *e.map_.waypoints.find(a.wp_id);
      m->change_route(target, 0.0, t, a.time);
      const RouteLanes* lanes = e.map_.lanes.route(a.wp_id);
      const double width = lanes && !lanes->lanes.empty() ? e.map_.lanes.lane(lanes->lanes.front()).width : 3.5;
      e.conflicts_.watch(a.actor, e.actors_.find(a.actor)->tracked.length, target, m->direction(), width, t + a.time);
    }

    void operator()(const LaneOffsetAction& a) const {
      if (!require_present(a.actor)) return;
      event(fmt::format("lane_offset: actor {} to {:+.2f} m over {:g} s", a.actor, a.value, a.time));
      ScriptedMotion* m = motion(a.actor);
      if (!m) return ego_only(a.actor, "lane_offset");
      m->plan_lateral({{a.value, a.time}}, t);
    }

    void operator()(const RouteMoveAction& a) const {
      if (!require_present(a.actor)) return;
      ScriptedMotion* m = motion(a.actor);
      if (!m) return ego_only(a.actor, "route_move");
      e.start_route_move(a, *m, t, out);
    }

    void operator()(const LightStateAction& a) const {
      if (!require_present(a.actor)) return;
      int& bits = e.signals_[a.actor];
      auto apply = [&](const std::optional<bool>& v, int bit) {
        if (v) bits = *v ? (bits | bit) : (bits & ~bit);
      };
      apply(a.blinker_left, kSignalBlinkerLeft);
      apply(a.blinker_right, kSignalBlinkerRight);
      apply(a.special1, kSignalEmergencyBlue);
      event(fmt::format("light_state: actor {} blinker_left {}, blinker_right {}, special1 {}", a.actor,
                        on_off(a.blinker_left), on_off(a.blinker_right), on_off(a.special1)));
      out.commands.push_back(SetSignals{e.actors_.find(a.actor)->tracked.sumo_id, bits});
    }

    void operator()(const SoundStateAction& a) const {
      if (!require_present(a.actor)) return;
      if (a.sound) e.sirens_[a.actor] = *a.sound;
      event(fmt::format("sound_state: actor {} siren {}", a.actor, on_off(a.sound)));
      out.commands.push_back(
          SetParameter{e.actors_.find(a.actor)->tracked.sumo_id, "orch.siren", e.siren(a.actor) ? "on" : "off"});
    }

    void operator()(const HandOverAction& a) const {
      e.hand_overs_.push_back({t, a});
      event(fmt::format("hand_over: {}{}", a.hand_over ? "on" : "off",
                        a.hand_over ? fmt::format(" (throttle {}, brake {}, steer {})", a.throttle.value_or(0.0),
                                                  a.brake.value_or(0.0), a.steer.value_or(0.0))
                                    : std::string{}));
      out.commands.push_back(SetParameter{"ego", "orch.hand_over", a.hand_over ? "1" : "0"});
    }

    void operator()(const EmptyAction&) const {}  // `{}` in the file does nothing
  };

  const std::size_t first_event = step_out.events.size();
  std::visit(Start{*this, now, step_out}, action.kind);
  // The structured field: which actor the action's events are about.
  std::visit(
      [&](const auto& a) {
        if constexpr (requires { a.actor; })
          for (std::size_t i = first_event; i < step_out.events.size(); ++i)
            if (!step_out.events[i].actor) step_out.events[i].actor = a.actor;
      },
      action.kind);
}

}  // namespace orch::engine
