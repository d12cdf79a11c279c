#pragma once
// The standard's transition shapes as functions of progress x in [0, 1]: step, linear,
// cubic (3x^2 - 2x^3) and sinusoidal ((1 - cos(pi x)) / 2), their slopes, and the duration
// a transition of size `change` takes for each dynamics dimension.
#include "openscenario/model.hpp"

namespace orch::openscenario {

double shape_value(DynamicsShape shape, double x);
// d(shape_value)/dx.
double shape_slope(DynamicsShape shape, double x);
// Peak of shape_slope over [0, 1] (0 for a step): a transition of `change` in T seconds
// changes at most change * peak_slope / T per second.
double peak_slope(DynamicsShape shape);

// Seconds for a transition of `change` (speed in m/s, or lateral metres) under `dynamics`:
// time: the value; rate: the peak rate of change equals the value; distance: the value is
// metres travelled at the mean of `speed_from` and `speed_to` (the shapes are symmetric).
double transition_duration(const TransitionDynamics& dynamics, double change, double speed_from, double speed_to);

// Seconds for a lateral shift of `change` metres whose peak lateral acceleration is `max_acc`.
double duration_for_lateral_acceleration(DynamicsShape shape, double change, double max_acc);

}  // namespace orch::openscenario
