#pragma once
// Distances between two entities for conditions and actions: in the first entity's frame
// or along the road, between reference points or between bounding boxes (freespace).
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

}  // namespace orch::openscenario
