#pragma once
// Distances between two entities for conditions and actions: in the first entity's frame
// or along the road, between reference points or between bounding boxes (freespace).
#include <optional>
#include <vector>

#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

struct Body {
  const EntityState* state = nullptr;
  const BoundingBox* box = nullptr;
};

// `distance_type`: longitudinal, lateral, cartesianDistance or euclidianDistance;
// `coordinate_system`: entity (the frame of `from`), road or lane (s and t of the road).
// Freespace distances are between the boxes, 0 when they overlap. Always >= 0.
double relative_distance(const Body& from, const Body& to, const std::string& distance_type,
                         const std::string& coordinate_system, bool freespace);

// relative_distance towards an entity ahead of `from`; none when `to` is not ahead (its
// reference point at most 1 um in front of `from`'s, along `from`'s heading in the entity
// frame, along its direction of travel on the road in road / lane coordinates).
// TimeHeadwayCondition needs it: the standard (1.3, TimeHeadwayCondition) assumes the
// reference entity "to be leading/ahead" and measures "the time it takes the triggering
// entity to reach the current position of the reference entity", which does not exist for
// one behind or alongside.
std::optional<double> distance_ahead(const Body& from, const Body& to, const opendrive::RoadNetwork& roads,
                                     const std::string& distance_type, const std::string& coordinate_system,
                                     bool freespace);

// Time until that distance reaches 0 at today's velocities: distance / closing rate, the
// rate from both bodies moved on at their speed and heading for kTtcHorizon seconds (exact
// for longitudinal distances on straight roads). Infinity when the distance does not shrink;
// 0 when freespace boxes already touch.
inline constexpr double kTtcHorizon = 0.1;  // s
double time_to_collision(const Body& from, const Body& to, const opendrive::RoadNetwork& roads,
                         const std::string& distance_type, const std::string& coordinate_system, bool freespace);

// RelativeClearanceCondition (model.hpp) for `self` among `others` (the entities it may
// consider, placed ones only). Lanes and distances are on `self`'s road; an entity on
// another road is never in the area (the checked stretch ends at the road's ends).
bool lanes_clear(const RelativeClearanceCondition& c, const Body& self, const std::vector<Body>& others,
                 const opendrive::RoadNetwork& roads);

// The two bounding boxes overlap (touching counts).
bool boxes_overlap(const Body& a, const Body& b);

}  // namespace orch::openscenario
