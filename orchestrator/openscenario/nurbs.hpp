#pragma once
// A Nurbs trajectory shape (OpenSCENARIO 1.0-1.3, Nurbs: order, ControlPoints with weight and
// optional time, Knots) as path points: the rational B-spline
//   C(u) = sum_i N_i,k(u) w_i P_i / sum_i N_i,k(u) w_i      (N: Cox-de Boor, k = order)
// sampled at equal steps of u over [knots[k-1], knots[n]] (n control points), about one
// sample every kClothoidStep metres of the control polygon. Pure geometry; positions are
// resolved by the caller.
//
// Times: the standard gives each control point an optional time and says no more. A control
// point's time is taken at the curve point it weighs most on (the peak of its basis
// function, where it "is" on the curve), and times are linear in u between those peaks: what
// esmini does, so a timed Nurbs is due at the same places in both players.
#include <optional>
#include <vector>

#include "openscenario/trajectory_motion.hpp"

namespace orch::openscenario {

struct NurbsControl {
  double x = 0, y = 0;
  double weight = 1;
  std::optional<double> time;  // all or none
  std::optional<double> z = std::nullopt;  // height in the world frame: all or none, weighed as x and y
};

// Throws MapError for a shape the formula cannot take: order < 1, fewer control points than
// the order, knots.size() != points + order, decreasing knots, a weight <= 0, an empty span.
std::vector<PathPoint> nurbs_points(const std::vector<NurbsControl>& controls, const std::vector<double>& knots,
                                    int order);

}  // namespace orch::openscenario
