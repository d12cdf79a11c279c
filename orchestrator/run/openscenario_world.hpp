#pragma once
// The OpenSCENARIO storyboard's entities as SUMO actors: which entity is the ego, the
// commands that put every placed entity where the storyboard has it (spawned on the SUMO
// lane netconvert made of its OpenDRIVE lane, then posed every step), and the way back
// from SUMO's vehicle centre to the entity's reference point for the trace. Pure.
#include <map>
#include <string>
#include <vector>

#include "sim/world.hpp"
#include "opendrive/sumo_lanes.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"
#include "run/openscenario_ego.hpp"

namespace orch {

// The ego's entity by the rule of openscenario_ego_choice.hpp ("" for none).
std::string choose_ego_entity(const openscenario::Scenario& scenario, const std::string& requested);

// Who drives the ego entity (openscenario_ego_choice.hpp, ego_driving).
enum class EgoDrive {
  Sumo,        // SUMO's car-following model (or the reference driver through SUMO's vehicle)
  External,    // as Sumo, until an ActivateControllerAction hands it to the plug-in (--ego-port)
  Storyboard,  // nobody: it follows the storyboard like every other entity
};

class OpenScenarioActors {
 public:
  // `ego` ("" for none) is the ego of metrics and the report. Driven (EgoDrive::Sumo or
  // External), SUMO's car-following model drives it: spawned and placed once where the
  // storyboard puts it, then only its desired speed follows the storyboard's speed target;
  // an external ego (--ego-port) takes it over once its controller is activated
  // (openscenario_ego.hpp). EgoDrive::Storyboard: it is placed every step like any entity.
  OpenScenarioActors(const openscenario::Scenario& scenario, const opendrive::SumoLaneIndex& lanes,
                     std::string ego, EgoDrive drive = EgoDrive::Sumo);

  // Commands for the entities' states now: a spawn for each newly placed entity, then a pose
  // for every placed scripted one (SUMO-driven ones: their desired speed when it changed).
  // An entity deleted (DeleteEntityAction) or invisible to traffic (VisibilityAction) is
  // taken out of SUMO, and spawned again (under a new SUMO id) when it comes back. A non-ego
  // entity whose controller is activated (Assign/ActivateControllerAction) is handed to
  // SUMO's driver like the ego. Throws MapError when an entity first appears where SUMO has no lane.
  std::vector<sim::Command> place(const std::map<std::string, openscenario::EntityState>& entities);
  // --controllers off: an activated controller hands nobody to SUMO's driver (every entity
  // but a driven ego stays the storyboard's).
  void disable_controllers() { controllers_ = false; }
  [[nodiscard]] bool controllers_enabled() const { return controllers_; }
  // Entities SUMO drives (the ego, activated controllers): the storyboard observes them.
  [[nodiscard]] std::vector<std::string> sumo_driven() const;
  [[nodiscard]] bool is_sumo_driven(const std::string& name) const;

  // The actors SUMO knows (spawned so far), for Simulator::read.
  [[nodiscard]] const std::vector<sim::TrackedActor>& tracked() const { return tracked_; }
  [[nodiscard]] const std::string& name_of(sim::ActorId id) const { return names_.at(static_cast<size_t>(id)); }
  // The entity's reference point (rear axle centre for vehicles) from SUMO's reported centre.
  [[nodiscard]] Vec2 reference_point(const sim::ActorState& state) const;
  // The entity's height above the road surface the storyboard gives (a relative position's dz).
  [[nodiscard]] double height_of(const std::string& name) const;
  [[nodiscard]] const std::string& ego() const { return ego_; }
  // SUMO, the reference driver or a plug-in drive the ego (false: it follows the storyboard).
  [[nodiscard]] bool ego_driven() const { return ego_driven_; }
  [[nodiscard]] const OpenScenarioEgo& ego_drive() const { return ego_drive_; }

 private:
  struct Body {
    sim::ActorId id = 0;
    ModelInfo model;
    double centre_x = 0, centre_y = 0;  // bounding box centre relative to the reference point
    bool spawned = false;
    int lives = 0;            // spawns so far; the SUMO id is the name, then name~2, name~3, ...
    std::string sumo_id;
    bool driven = false;      // by SUMO (the ego, an activated controller)
    double desired_speed = -1;  // last sent to a SUMO-driven one
    std::size_t route_version = 0;  // of the entity's route plan its SUMO route was made from
    double height = 0;              // above the road (the storyboard's)
  };
  [[nodiscard]] Vec2 centre_of(const Body& body, const opendrive::Pose2& pose) const;
  // SUMO edges for a SUMO-driven entity: its road, its planned lanes, then straight on.
  [[nodiscard]] std::vector<std::string> sumo_route_of(const openscenario::EntityState& state) const;
  void set_route(Body& body, const openscenario::EntityState& state, std::vector<sim::Command>& out);
  void spawn(const std::string& name, Body& body, const openscenario::EntityState& state,
             std::vector<sim::Command>& out);

  const opendrive::SumoLaneIndex& lanes_;
  std::string ego_;
  bool ego_driven_ = true;
  bool controllers_ = true;  // false: --controllers off
  OpenScenarioEgo ego_drive_;
  std::map<std::string, Body> bodies_;
  std::vector<std::string> names_;  // by actor id
  std::vector<sim::TrackedActor> tracked_;
};

}  // namespace orch
