#pragma once
#include <cmath>
// How the storyboard moves a scripted entity, in the OpenDRIVE road frame: along its lane
// at the speed its speed profile gives, shifted laterally by lane changes and lane offsets.
// The speed is the speed along the path: during a lateral shift the progress along s is
// sqrt(v^2 - v_lat^2), as other OpenSCENARIO players move entities.
#include <optional>
#include <string>

#include "opendrive/lane_graph.hpp"
#include "opendrive/road_network.hpp"
#include "openscenario/model.hpp"
#include "openscenario/trajectory_motion.hpp"

namespace orch::openscenario {

// speed(t) = from + (to - from) * shape((t - start) / duration)
struct SpeedProfile {
  double start = 0, duration = 0, from = 0, to = 0;
  DynamicsShape shape = DynamicsShape::Step;
  [[nodiscard]] double at(double t) const;
  [[nodiscard]] bool done(double t) const { return t - start >= duration - 1e-9; }
};

// lane offset(t) = from + (to - from) * shape((t - start) / duration), relative to `lane`'s centre.
struct LateralProfile {
  double start = 0, duration = 0, from = 0, to = 0;
  DynamicsShape shape = DynamicsShape::Step;
  // A LaneOffsetAction's, moved as esmini moves it (the standard gives the shape over the
  // action's duration, not how a player steps it): its shape runs one step behind the
  // action's start (the offset at t is the shape at t - dt, so its first step keeps the
  // offset it starts from and it ends one step after start + duration), and the entity
  // keeps its full speed along its lane meanwhile (esmini's default controller moves it
  // along s; a LaneChangeAction moves it along its path, sqrt(v^2 - v_lat^2) along s).
  // OSC-ALKS 4.1_2 chains four sinusoidal swerves by endTransition; each takes one step
  // more than its duration in esmini.
  bool lane_offset = false;
  // A LaneChangeAction whose dynamicsDimension is distance: its shape runs over `distance`
  // metres travelled from `odometer_start` (the entity's odometer then), whatever its speed
  // on the way (a slowing car takes longer); `duration` is the distance at its speed at the
  // start, the clock's scale. 0: the shape runs in time.
  double distance = 0, odometer_start = 0;
  [[nodiscard]] double at(double t) const;
  [[nodiscard]] double rate(double t) const;  // m/s of the clock, positive to the left of the road
  [[nodiscard]] bool done(double t) const { return t - start >= duration - 1e-9; }
  // The time on the shape's clock at t, after a step of dt that brought the entity's
  // odometer to `odometer`.
  [[nodiscard]] double clock(double t, double dt, double odometer) const {
    if (distance > 0) return start + duration * (odometer - odometer_start) / distance;
    return lane_offset ? t - dt : t;
  }
  // The lateral speed (m/s) at clock time c for an entity at `speed`.
  [[nodiscard]] double rate_at(double c, double speed) const {
    return distance > 0 && duration > 0 ? rate(c) * std::abs(speed) * duration / distance : rate(c);
  }
};

struct EntityState {
  bool placed = false;
  std::string road_id;  // "" on no road (a scenario without one): `pose` alone is its place
  double s = 0;
  int lane = 0;
  double offset = 0;  // from the lane centre, positive to the left (t direction)
  double t = 0;       // lateral position on the road (lane centre + offset), set by update_pose
  double speed = 0;
  double acceleration = 0;
  double lateral_rate = 0;
  double odometer = 0;
  // The way the entity drives along its road: +1 along s, -1 against s; 0: its lane's driving
  // direction. Set where it is placed (from its heading), kept through lane changes (a car
  // changing into the oncoming lane keeps going its way), taken from the lane graph at links.
  int direction = 0;
  // Height of the reference point above the road surface: a relative position's dz (a bike
  // carried on a car, esmini's drop-bike.xosc); 0 on the road.
  double height = 0;
  opendrive::Pose2 pose;  // reference point in the inertial frame
  std::optional<SpeedProfile> speed_profile;
  std::optional<LateralProfile> lateral_profile;
  // A running LaneChangeAction comes before the running SpeedAction in the storyboard: the
  // lane change moves the entity along its lane with the speed from before this step's
  // speed update. The standard leaves the order of actions within a step open; esmini steps
  // the running actions in storyboard order and its lane change moves the entity itself with
  // the speed it finds (cut-in_simple.xosc: braking during the cut-in gains 0.0125 m a step).
  bool lane_change_before_speed = false;
  bool controller_active = false;  // ActivateControllerAction (the ego's system under test)
  std::string controller;          // its controller's name ("" = none; AssignControllerAction replaces it)
  VisibilityAction visibility;     // graphics, traffic, sensors
  std::optional<PathMotion> path;  // FollowTrajectoryAction: moves along this instead of its lane
  // AssignRouteAction / AcquirePositionAction: the waypoints mapped onto the roads, and how
  // many of them the entity has passed.
  struct Waypoint {
    std::string road_id;
    double s = 0;
    int lane = 0;
  };
  std::vector<Waypoint> route;
  std::size_t route_passed = 0;
  // The lanes the route planned (openscenario/route_plan.hpp), taken in order where a lane
  // continues on several (road_following.hpp); route_plan_next is the next one to take. A
  // closed route's plan goes on from route_plan_loop after its last lane.
  std::vector<opendrive::LaneEntry> route_plan;
  std::size_t route_plan_next = 0;
  std::optional<std::size_t> route_plan_loop;
  std::size_t route_version = 0;  // counts the plans made (a simulator re-routes on a change)
};

// Direction of travel along s: +1 on right lanes, -1 on left lanes (right-hand traffic;
// mirrored for left-hand traffic roads).
int travel_direction(const opendrive::Road& road, int lane);
// The way `state` drives along `road` (its own direction, else its lane's).
int travel_direction(const EntityState& state, const opendrive::Road& road);
// The direction along `road` at s of a body heading `heading`: +1 along s, -1 against it.
int direction_of_heading(const opendrive::Road& road, double s, double heading);

// Advances `state` from t - dt to t along its road. Profiles that finish are left in place
// (the runtime reads done() and ends their actions).
void advance(EntityState& state, const opendrive::RoadNetwork& roads, double t, double dt);
// Recomputes the inertial pose from (road, s, lane, offset) and the lateral rate.
void update_pose(EntityState& state, const opendrive::RoadNetwork& roads);
// The road coordinates (road, s, lane, offset, t) of the state's inertial pose: for an entity
// placed by a trajectory or a simulator. Off every lane it keeps its last lane (s and offset
// from it follow the pose while it stays beside the same road).
void relocate(EntityState& state, const opendrive::RoadNetwork& roads);
// The height of the road surface under a point: the lane's surface there, 0 off every lane
// (trace.csv's z is this plus the entity's `height`). A position given in the world's z (a
// WorldPosition's) becomes a height above it.
double surface_height(const opendrive::RoadNetwork& roads, const opendrive::Pose2& at);

}  // namespace orch::openscenario
