#pragma once
// The reference driver (reference_driver/) set up for a run of either scenario format: the
// ego's lane as its path, the ego's size, which actors are pedestrians or obstacles.
#include <optional>

#include "scenario_executor_engine/engine.hpp"
#include "map/lane_map.hpp"
#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"
#include "reference_driver/ego_model.hpp"
#include "reference_driver/reference_ego.hpp"

namespace orch {

// ScenarioExecutor runs (after Engine::start, which places the ego on its route): the ego
// drives along its waypoint route. Nullopt unless the choice is r157. Throws ScenarioError
// for a bad r157 parameter (evaluation files are checked when loaded).
std::optional<reference_driver::ReferenceEgo> reference_ego_for(const EgoModelChoice& choice, const engine::Engine& engine,
                                                                const LaneMap& lanes, double step);

// OpenSCENARIO runs: the ego drives along the centre of the OpenDRIVE lane it starts on.
std::optional<reference_driver::ReferenceEgo> reference_ego_for(const EgoModelChoice& choice,
                                                                const openscenario::Scenario& scenario,
                                                                const opendrive::RoadNetwork& roads,
                                                                const std::string& ego,
                                                                const openscenario::EntityState& start, double step);

// OpenSCENARIO runs: the centre line of the OpenDRIVE lane the ego starts in, in its driving
// direction, and which entities are pedestrians or obstacles.
reference_driver::DrivingPath lane_path(const opendrive::RoadNetwork& roads, const openscenario::EntityState& start);
reference_driver::ObjectKinds object_kinds(const openscenario::Scenario& scenario);

// r157 parameters with the overrides applied; throws ScenarioError naming the bad key.
reference_driver::R157Parameters r157_parameters(const EgoModelChoice& choice);

}  // namespace orch
