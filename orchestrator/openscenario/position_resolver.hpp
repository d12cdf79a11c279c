#pragma once
// Where an OpenSCENARIO Position is, in the OpenDRIVE inertial frame, computed from the
// OpenDRIVE geometry itself (never from SUMO's lane lengths, which differ from s on curves).
// Pure: the poses of the entities a relative position refers to come from the caller.
#include <functional>
#include <optional>
#include <string>

#include "opendrive/road_network.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

struct ResolvedPosition {
  opendrive::Pose2 pose;  // x, y, heading of the entity's reference point
  // The road point of the position (road, s, t, lane) when it lies on a road.
  std::optional<opendrive::RoadCoordinate> road;
  std::optional<int> lane;
};

// Pose of an entity's reference point by name; nullopt when the entity has none yet.
using EntityPoseLookup = std::function<std::optional<opendrive::Pose2>(const std::string&)>;

// Lane id `d_lane` lanes from `lane` counted in lane ids (positive = towards higher ids),
// skipping the centre lane 0.
int shifted_lane(int lane, int d_lane);

class PositionResolver {
 public:
  explicit PositionResolver(const opendrive::RoadNetwork& roads) : roads_(roads) {}
  // Throws MapError (no such road or lane, an entity without a position) naming what is missing.
  [[nodiscard]] ResolvedPosition resolve(const Position& position, const EntityPoseLookup& entity_pose) const;
  // The road point and lane of an inertial point (the nearest road).
  [[nodiscard]] ResolvedPosition locate(const opendrive::Pose2& pose) const;

 private:
  const opendrive::RoadNetwork& roads_;
};

}  // namespace orch::openscenario
