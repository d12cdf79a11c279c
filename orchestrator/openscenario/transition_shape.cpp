#include "openscenario/transition_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace orch::openscenario {

double shape_value(DynamicsShape shape, double x) {
  x = std::clamp(x, 0.0, 1.0);
  switch (shape) {
    case DynamicsShape::Step: return 1.0;
    case DynamicsShape::Linear: return x;
    case DynamicsShape::Cubic: return x * x * (3.0 - 2.0 * x);
    case DynamicsShape::Sinusoidal: return 0.5 * (1.0 - std::cos(std::numbers::pi * x));
  }
  return 1.0;
}

double shape_slope(DynamicsShape shape, double x) {
  if (x < 0.0 || x > 1.0) return 0.0;
  switch (shape) {
    case DynamicsShape::Step: return 0.0;
    case DynamicsShape::Linear: return 1.0;
    case DynamicsShape::Cubic: return 6.0 * x * (1.0 - x);
    case DynamicsShape::Sinusoidal: return 0.5 * std::numbers::pi * std::sin(std::numbers::pi * x);
  }
  return 0.0;
}

double peak_slope(DynamicsShape shape) {
  switch (shape) {
    case DynamicsShape::Step: return 0.0;
    case DynamicsShape::Linear: return 1.0;
    case DynamicsShape::Cubic: return 1.5;
    case DynamicsShape::Sinusoidal: return 0.5 * std::numbers::pi;
  }
  return 0.0;
}

double transition_duration(const TransitionDynamics& dynamics, double change, double speed_from, double speed_to) {
  if (dynamics.shape == DynamicsShape::Step) return 0.0;
  switch (dynamics.dimension) {
    case DynamicsDimension::Time: return dynamics.value;
    case DynamicsDimension::Rate:
      return dynamics.value > 0 ? std::abs(change) * peak_slope(dynamics.shape) / dynamics.value : 0.0;
    case DynamicsDimension::Distance: {
      const double mean = 0.5 * (std::abs(speed_from) + std::abs(speed_to));
      return mean > 0 ? dynamics.value / mean : 0.0;
    }
  }
  return 0.0;
}

double duration_for_lateral_acceleration(DynamicsShape shape, double change, double max_acc) {
  const double d = std::abs(change);
  if (max_acc <= 0 || d == 0) return 0.0;
  switch (shape) {
    case DynamicsShape::Step: return 0.0;
    case DynamicsShape::Sinusoidal: return std::numbers::pi * std::sqrt(d / (2.0 * max_acc));  // peak d/2 (pi/T)^2
    case DynamicsShape::Cubic: return std::sqrt(6.0 * d / max_acc);                             // peak 6 d / T^2
    case DynamicsShape::Linear: return 0.0;  // unbounded acceleration at the ends: as a step
  }
  return 0.0;
}

}  // namespace orch::openscenario
