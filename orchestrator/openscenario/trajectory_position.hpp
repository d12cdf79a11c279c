#pragma once
// TrajectoryPosition (OpenSCENARIO 1.1): the path of a Trajectory (Polyline, Clothoid,
// ClothoidSpline, Nurbs; closed or not) as map/'s TrajectoryPath, so the position resolver
// can put a position s metres along it and t to its left. The same geometry as a
// FollowTrajectoryAction's path (trajectory_motion.hpp, nurbs.hpp), without times.
#include <memory>

#include "map/position.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

std::shared_ptr<const position::TrajectoryPath> trajectory_path_of(Trajectory trajectory);

}  // namespace orch::openscenario
