#pragma once
// The Trajectory of the OpenSCENARIO model: the shape a FollowTrajectoryAction follows and a
// TrajectoryPosition measures along (kept apart from model.hpp, which holds it in both).

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "map/position.hpp"

namespace orch::openscenario {

using position::Position;

// Trajectories: positions resolved when the action starts (relative ones against the
// entities then). Vertex times are in the trajectory's own time (see TrajectoryTiming).
struct TrajectoryVertex {
  std::optional<double> time;
  Position position;
};
struct PolylineShape { std::vector<TrajectoryVertex> vertices; };
struct ClothoidShape {
  Position start;
  double curvature = 0, curvature_dot = 0, length = 0;
  std::optional<double> start_time, stop_time;
};
// ClothoidSpline (1.3): segments joined end to start. A segment starts at its PositionStart
// (its heading + hOffset) or, without one, where the segment before ends (the first: where
// the entity is when the action starts), heading + hOffset; its curvature changes linearly
// from curvatureStart to curvatureEnd over its length. Timed when every segment has a
// timeStart and the spline a timeEnd.
struct ClothoidSplineSegment {
  std::optional<Position> start;
  double curvature_start = 0, curvature_end = 0, length = 0, heading_offset = 0;
  std::optional<double> time_start;
};
struct ClothoidSplineShape {
  std::vector<ClothoidSplineSegment> segments;
  std::optional<double> time_end;
};
// Nurbs: order, control points (weight, optional time), knots (openscenario/nurbs.hpp).
struct NurbsControlPoint {
  std::optional<double> time;
  double weight = 1;
  Position position;
};
struct NurbsShape {
  int order = 0;
  std::vector<NurbsControlPoint> points;
  std::vector<double> knots;
};
struct Trajectory {
  std::string name;
  bool closed = false;
  std::variant<PolylineShape, ClothoidShape, NurbsShape, ClothoidSplineShape> shape;
};

}  // namespace orch::openscenario
