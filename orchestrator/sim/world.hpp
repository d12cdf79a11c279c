#pragma once
// The values that cross the simulator seam: what a scenario language's runtime reads each
// step (WorldSnapshot) and what it asks the simulator to do (Command). Plain data, below
// both scenario languages (the ScenarioExecutor engine, the OpenSCENARIO storyboard) and the
// SUMO adapters, so that scenario semantics are testable without SUMO and a run is replayable.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/polyline.hpp"
#include "sim/actor.hpp"

namespace orch::sim {

// SUMO vehicle signal bits the format's lights map to (TraCI VEH_SIGNAL_*).
inline constexpr int kSignalBlinkerRight = 1 << 0;
inline constexpr int kSignalBlinkerLeft = 1 << 1;
inline constexpr int kSignalEmergencyBlue = 1 << 11;  // special1: emergency vehicles' beacon

// One scenario actor as the simulator knows it.
struct TrackedActor {
  ActorId id = 0;
  std::string sumo_id;  // "ego" for the ego, "actor<id>" for the others
  ActorKind kind = ActorKind::Vehicle;
  double length = 0;
  double width = 0;
};

struct ActorState {
  ActorId id = 0;
  bool present = false;  // false before insertion or after the actor left the simulation
  Vec2 position{0, 0};   // centre of the actor, map frame, m
  double heading = 0;    // rad, counter-clockwise from +x
  double speed = 0;      // m/s
  double accel = 0;      // m/s^2
  std::string edge;      // SUMO edge ("" off-road)
  int lane = -1;         // SUMO lane index, 0 = rightmost
  double lane_pos = 0;   // SUMO lane position of the centre, m
  std::optional<double> lat_offset;  // m from the lane centre, + = left (nullopt: simulator cannot tell)
  int signals = 0;       // SUMO signal bits
  bool siren = false;    // sound_state (scripted actors)
};

// A collision SUMO reported in the last step (ids are SUMO ids).
struct SimCollision {
  std::string collider;
  std::string victim;
  std::string type;  // "collision", "frontal", "junction", ...
  std::string lane;
  double pos = 0;
};

// A SUMO vehicle that is not a scenario actor (background traffic), near an actor: what the
// collision test checks against and what --trace-background writes.
struct NearbyVehicle {
  std::string sumo_id;
  Vec2 position{0, 0};  // centre, map frame
  double heading = 0;   // rad, counter-clockwise from +x
  double speed = 0;
  double length = 0;
  double width = 0;
};

inline constexpr double kLongWait = 60.0;  // s

struct WorldSnapshot {
  double time = 0;
  std::vector<ActorState> actors;  // same order as the tracked actors
  std::vector<SimCollision> collisions;
  std::vector<NearbyVehicle> nearby;  // background vehicles close to any actor
  // Vehicles spawned as traffic (SpawnVehicle::traffic), wherever they are, in id order;
  // one that left SUMO (its route ended, removed) is no longer here.
  std::vector<NearbyVehicle> traffic;
  int other_vehicles = 0;  // SUMO vehicles that are not scenario actors
  // Vehicles standing still for more than kLongWait seconds (a junction that does not
  // clear), counted once a simulated second; the last count in between.
  int long_waiting = 0;

  [[nodiscard]] const ActorState* find(ActorId id) const {
    for (const auto& a : actors)
      if (a.id == id) return &a;
    return nullptr;
  }
};

// ---------------------------------------------------------------- commands
struct SpawnVehicle {
  TrackedActor actor;
  ModelInfo model;
  std::string color;                 // "rrggbb" or ""
  bool scripted = true;              // placed by the orchestrator every step (no SUMO driver)
  std::vector<std::string> route;    // SUMO edges
  std::string edge;
  int lane = 0;
  double lane_pos = 0;               // SUMO lane position of the centre
  double speed = 0;                  // m/s at insertion
  double max_speed = 0;              // m/s, SUMO-driven vehicles only (0 = type default)
  bool keep_lateral = false;         // SUMO-driven: keep the lateral offset it is placed at
  // Background traffic a scenario adds (OpenSCENARIO TrafficActions): SUMO drives it, it is
  // no scenario actor (not in Simulator::read's list), and WorldSnapshot::traffic reports it.
  bool traffic = false;
};
struct SpawnPerson {
  TrackedActor actor;
  ModelInfo model;
  std::string color;
  std::string edge;
  double lane_pos = 0;
};
// Put an actor's centre at `position` facing `heading` (scripted actors, every step).
struct SetPose {
  std::string sumo_id;
  ActorKind kind = ActorKind::Vehicle;
  double length = 0;
  Vec2 position{0, 0};
  double heading = 0;
  double speed = 0;
  std::string edge;  // lane hint
  int lane = 0;
  int signals = 0;   // SUMO forgets signals of vehicles it does not drive: sent with every pose
  bool scripted = true;  // false: a one-off placement of a SUMO-driven vehicle (speed left to SUMO)
  bool centred = false;  // within half a metre of the lane's centre: SUMO must put it on that lane
};
struct SetSignals {
  std::string sumo_id;
  int signals = 0;
};
struct SetMaxSpeed {  // the desired speed of a SUMO-driven vehicle
  std::string sumo_id;
  double speed = 0;
};
struct SetStop {  // a SUMO-driven vehicle stops with its centre here and stays
  std::string sumo_id;
  std::string edge;
  int lane = 0;
  double lane_pos = 0;  // of the centre
  double length = 0;
};
struct SetParameter {
  std::string sumo_id;
  std::string key;
  std::string value;
};

struct RemoveActor {  // takes a spawned actor out of the simulation (OpenSCENARIO DeleteEntityAction)
  std::string sumo_id;
  ActorKind kind = ActorKind::Vehicle;
};
struct ReleaseActor {  // a scripted vehicle is driven by SUMO from now on, at most at `max_speed`
  std::string sumo_id;
  double max_speed = 0;
};

// A SUMO-driven vehicle's route from now on (OpenSCENARIO routes and road links): the
// simulator keeps the part from the vehicle's current route edge on.
struct SetRoute {
  std::string sumo_id;
  std::vector<std::string> edges;
};

// The speed a built-in ego model (reference_driver/) drives in the next step: SUMO drives
// exactly this speed (speed mode 0 from the first one on: no checks of SUMO's own).
struct DriveSpeed {
  std::string sumo_id;
  double speed = 0;
};

// A traffic light's links from now on (OpenSCENARIO traffic signals): `links` has one SUMO
// signal colour per link index ('r', 'y', 'G', ...) or '-' where the light keeps its state;
// the light leaves its own program and holds these states until told otherwise.
struct SetTrafficLight {
  std::string tls_id;
  std::string links;
};

using Command = std::variant<SpawnVehicle, SpawnPerson, SetPose, SetSignals, SetMaxSpeed, SetStop, SetParameter,
                             RemoveActor, ReleaseActor, DriveSpeed, SetRoute, SetTrafficLight>;

}  // namespace orch::sim
