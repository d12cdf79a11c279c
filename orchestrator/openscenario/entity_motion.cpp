#include "openscenario/entity_motion.hpp"

#include <algorithm>
#include <cmath>

#include "openscenario/road_following.hpp"
#include "openscenario/trajectory_follow.hpp"
#include "openscenario/transition_shape.hpp"

namespace orch::openscenario {

double SpeedProfile::at(double t) const {
  if (duration <= 0) return to;
  return from + (to - from) * shape_value(shape, (t - start) / duration);
}

double LateralProfile::at(double t) const {
  if (duration <= 0) return to;
  return from + (to - from) * shape_value(shape, (t - start) / duration);
}

double LateralProfile::rate(double t) const {
  if (duration <= 0) return 0.0;
  return (to - from) * shape_slope(shape, (t - start) / duration) / duration;
}

int travel_direction(const opendrive::Road& road, int lane) { return opendrive::lane_direction(road, lane); }

int travel_direction(const EntityState& state, const opendrive::Road& road) {
  return state.direction != 0 ? state.direction : travel_direction(road, state.lane);
}

int direction_of_heading(const opendrive::Road& road, double s, double heading) {
  return std::cos(heading - road.plan_view.pose(std::clamp(s, 0.0, road.length)).heading) >= 0 ? 1 : -1;
}

namespace {

// How the lane's centre moves sideways along the road, dt/ds at s (a lane that narrows or
// widens beside it, a lane offset): a central difference within s's lane section, whose
// lanes the id names (across a section border the ids may change).
double lane_center_slope(const opendrive::Road& road, int lane, double s) {
  const std::size_t i = opendrive::section_index(road, s);
  const double from = road.sections[i].s;
  const double to = i + 1 < road.sections.size() ? road.sections[i + 1].s - 1e-6 : road.length;
  constexpr double kHalfStep = 0.01;  // m
  const double a = std::max(s - kHalfStep, from);
  const double b = std::min(s + kHalfStep, to);
  if (b - a < 1e-9) return 0.0;
  return (road.lane_center_t(lane, b) - road.lane_center_t(lane, a)) / (b - a);
}

}  // namespace

void update_pose(EntityState& state, const opendrive::RoadNetwork& roads) {
  if (state.road_id.empty()) return;  // on no road: the pose is its place
  const opendrive::Road& road = roads.road(state.road_id);
  const double s = std::clamp(state.s, 0.0, road.length);
  state.t = road.lane_center_t(state.lane, s) + state.offset;
  const opendrive::Pose2 p = road.world(s, state.t);
  const int direction = travel_direction(state, road);
  const double along = std::sqrt(std::max(state.speed * state.speed - state.lateral_rate * state.lateral_rate, 0.0));
  // The entity faces where it moves: along its lane at `along` m/s, sideways at the action's
  // lateral rate plus the lane centre's own drift (dt/ds per metre of its path, 1 - k t of
  // s on a curve), as the lane carries it (trailers.xosc: road 202's lane 2 shifts 3.75 m
  // right over 30 m, and the tractor turns with it; its trailers follow the tractor's heading).
  const double stretch = std::max(1.0 - road.plan_view.curvature(s) * state.t, 0.1);
  const double drift = direction * lane_center_slope(road, state.lane, s) / stretch;
  // Moving along +s, a leftward rate turns the heading left; along -s, right. Standing, it
  // faces along its lane.
  const double yaw = along > 0 ? std::atan2(state.lateral_rate + drift * along, along)
                     : state.lateral_rate != 0 ? std::atan2(state.lateral_rate, 1e-9)
                                               : std::atan(drift);
  double heading = direction > 0 ? p.heading + yaw : p.heading + M_PI - yaw;
  heading = std::fmod(heading, 2 * M_PI);
  if (heading < 0) heading += 2 * M_PI;
  state.pose = {p.x, p.y, heading};
}

void relocate(EntityState& state, const opendrive::RoadNetwork& roads) {
  const auto on_road = roads.to_road(state.pose.x, state.pose.y);
  if (!on_road) return;
  const opendrive::Road& road = roads.road(on_road->road_id);
  auto lane = road.lane_at(on_road->s, on_road->t);
  if (!lane || *lane == 0) {
    // Off the lanes (a pedestrian on the verge): measured from its last lane on this road.
    if (state.road_id != road.id || state.lane == 0) return;
    lane = state.lane;
  }
  state.road_id = on_road->road_id;
  state.s = on_road->s;
  state.direction = direction_of_heading(road, on_road->s, state.pose.heading);
  state.lane = *lane;
  state.t = on_road->t;
  state.offset = on_road->t - road.lane_center_t(*lane, on_road->s);
}

double surface_height(const opendrive::RoadNetwork& roads, const opendrive::Pose2& at) {
  const auto c = roads.to_road(at.x, at.y);
  if (!c) return 0.0;
  const opendrive::Road& road = roads.road(c->road_id);
  if (!road.lane_at(c->s, c->t)) return 0.0;
  return opendrive::surface_pose(road, c->s, c->t, at.heading).z;
}

namespace {

// Along a trajectory: timed paths give the distance (and so the speed), untimed ones are
// driven at the entity's own speed (its speed profile's).
void advance_on_path(EntityState& state, const opendrive::RoadNetwork& roads, double t, double dt) {
  PathMotion& path = *state.path;
  const double previous_speed = state.speed;
  const double before = path.distance;
  if (path.follower) {  // followingMode "follow": tracked under the entity's own limits
    const std::optional<double> profile =
        state.speed_profile ? std::optional<double>(state.speed_profile->at(t)) : std::nullopt;
    (void)follow_step(path, state.pose, state.speed, profile, t, dt);
  } else {
    if (path.timed) {
      path.distance = path.distance_at(t);
      state.speed = dt > 0 ? (path.distance - before) / dt : 0.0;
    } else {
      if (state.speed_profile) state.speed = state.speed_profile->at(t);
      // A negative speed reverses along the path: it still goes from its start to its end,
      // the entity facing the other way (esmini's trailer_connect.xosc backs a car onto a
      // trailer along a path written behind it, Orientation h=pi relative to the car).
      path.distance = std::min(path.length(), before + std::abs(state.speed) * dt);
    }
    // The step's travel left when an untimed path ends within the step: the entity keeps its
    // speed for the whole step, on along the last segment (the action ends at the end, the
    // entity does not stop there; esmini moves the same way).
    const double beyond = path.timed ? 0.0 : std::max(0.0, before + std::abs(state.speed) * dt - path.length());
    state.pose = path.pose_at(path.distance);
    state.pose.x += beyond * std::cos(state.pose.heading);
    state.pose.y += beyond * std::sin(state.pose.heading);
    if (!path.timed && state.speed < 0) {
      state.pose.heading = std::fmod(state.pose.heading + M_PI, 2 * M_PI);
      if (state.pose.heading < 0) state.pose.heading += 2 * M_PI;
    }
  }
  state.acceleration = dt > 0 ? (state.speed - previous_speed) / dt : 0.0;
  state.lateral_rate = 0.0;
  relocate(state, roads);
  // A path through WorldPositions with z (a camera's flight): its height, over the road under it.
  if (const std::optional<double> z = path.z_at(path.distance)) state.height = *z - surface_height(roads, state.pose);
}

// One step of the entity's motion: along its path, its lane or (on no road) its heading.
void move_one_step(EntityState& state, const opendrive::RoadNetwork& roads, double t, double dt) {
  if (state.path) {
    advance_on_path(state, roads, t, dt);
    return;
  }
  const double previous_speed = state.speed;
  if (state.speed_profile) state.speed = state.speed_profile->at(t);
  state.acceleration = dt > 0 ? (state.speed - previous_speed) / dt : 0.0;
  state.lateral_rate = 0.0;
  if (state.lateral_profile) {
    // By distance: where the step's travel takes the entity's odometer.
    const double clock = state.lateral_profile->clock(t, dt, state.odometer + std::abs(state.speed) * dt);
    state.offset = state.lateral_profile->at(clock);
    state.lateral_rate = state.lateral_profile->rate_at(clock, state.speed);
  }
  // Standing still, nothing moves it: it keeps its pose, also a heading across its lane that
  // its position's Orientation gave it (a parked car, esmini's parking_demo.xosc, faces the
  // kerb until it drives off; esmini leaves a standing entity where it is).
  if (previous_speed == 0 && state.speed == 0 && !state.lateral_profile) return;
  if (state.road_id.empty()) {  // on no road (a scenario without one): straight on along its heading
    state.pose.x += state.speed * dt * std::cos(state.pose.heading);
    state.pose.y += state.speed * dt * std::sin(state.pose.heading);
    return;
  }
  const opendrive::Road& road = roads.road(state.road_id);
  // The speed it travels this step with (EntityState::lane_change_before_speed).
  const double travel = state.lane_change_before_speed && state.lateral_profile ? previous_speed : state.speed;
  // Its speed along its path, less what a lane change takes sideways (a lane offset's
  // sideways motion is on top: LateralProfile::lane_offset).
  const double sideways = state.lateral_profile && state.lateral_profile->lane_offset ? 0.0 : state.lateral_rate;
  // A negative speed drives backwards (esmini's light_state.xosc reverses at -3 m/s).
  const double along = std::copysign(std::sqrt(std::max(travel * travel - sideways * sideways, 0.0)), travel);
  // The speed is along the entity's own path, at lateral position t: on a curve of
  // curvature k that path is (1 - k t) times as long as the reference line.
  const double stretch = 1.0 - road.plan_view.curvature(state.s) * state.t;
  const std::size_t section = opendrive::section_index(road, std::clamp(state.s, 0.0, road.length));
  const double s_before = state.s;
  state.s += travel_direction(state, road) * along * dt / (stretch > 0.1 ? stretch : 0.1);
  follow_links(state, roads, section, s_before);  // lane sections, and on past the road's end
  leave_vanished_lane(state, roads);
  update_pose(state, roads);
}

}  // namespace

void advance(EntityState& state, const opendrive::RoadNetwork& roads, double t, double dt) {
  if (!state.placed) return;
  const opendrive::Pose2 before = state.pose;
  move_one_step(state, roads, t, dt);
  // The traveled distance (TraveledDistanceCondition) is the sum of the straight distances
  // between the entity's positions at successive steps. The standard does not say how it is
  // measured; esmini's odometer adds up these chords, which on a curve fall short of the
  // arc by about L^3 / (24 R^2) a step: pedestrian.xosc's Ego reaches 5 m at 10 m/s on a
  // curve one step after the 10 steps of 0.5 m along its lane, in both players.
  state.odometer += std::hypot(state.pose.x - before.x, state.pose.y - before.y);
}

}  // namespace orch::openscenario
