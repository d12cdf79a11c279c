#include "metrics/lane_keeping.hpp"

#include <algorithm>
#include <cmath>

namespace orch::metrics {

double lane_departure(double lateral, double relative_heading, double length, double width, double lane_width) {
  const double half_extent =
      width / 2 * std::abs(std::cos(relative_heading)) + length / 2 * std::abs(std::sin(relative_heading));
  return std::max(0.0, std::abs(lateral) + half_extent - lane_width / 2);
}

}  // namespace orch::metrics
