#include "opendrive/road_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checked_numeric.hpp"
#include "opendrive/road_network.hpp"

namespace orch::opendrive {
namespace {

// The largest |r.value(x)| for x in [0, span]: at an end or where the slope is zero.
double max_abs(const CubicRecord& r, double span) {
  span = std::max(span, 0.0);
  double m = std::max(std::abs(r.value(0.0)), std::abs(r.value(span)));
  const auto at = [&](double x) {
    if (x > 0 && x < span) m = std::max(m, std::abs(r.value(x)));
  };
  if (r.d != 0) {  // slope b + 2 c x + 3 d x^2
    const double disc = 4 * r.c * r.c - 12 * r.d * r.b;
    if (disc >= 0) {
      at((-2 * r.c + std::sqrt(disc)) / (6 * r.d));
      at((-2 * r.c - std::sqrt(disc)) / (6 * r.d));
    }
  } else if (r.c != 0) {
    at(-r.b / (2 * r.c));
  }
  return m;
}

// The largest |value| of piecewise records over [0, end] (each record runs to the next).
double max_abs(const std::vector<CubicRecord>& records, double end) {
  double m = 0.0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const double to = i + 1 < records.size() ? records[i + 1].s : end;
    m = std::max(m, max_abs(records[i], to - records[i].s));
  }
  return m;
}

}  // namespace

double lateral_reach(const Road& road) {
  const double end = std::max(road.length, road.plan_view.length());
  double widest = 0.0;
  for (std::size_t i = 0; i < road.sections.size(); ++i) {
    const LaneSection& section = road.sections[i];
    const double section_end = (i + 1 < road.sections.size() ? road.sections[i + 1].s : end) - section.s;
    for (const auto* side : {&section.left, &section.right}) {
      double sum = 0.0;
      for (const Lane& lane : *side) sum += max_abs(lane.widths, section_end);
      widest = std::max(widest, sum);
    }
  }
  return max_abs(road.lane_offsets, end) + widest;
}

std::uint64_t RoadGrid::key(std::int64_t cx, std::int64_t cy) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(cx)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(cy));
}

std::int64_t RoadGrid::cell_of(double v) const {
  return grid_cell(v, cell_);  // core/checked_numeric.hpp: NaN and far values stay in the grid
}

RoadGrid::RoadGrid(const std::vector<Road>& roads) {
  // A point a road holds on a lane lies within lateral_reach (+ 1e-3, to_road's tolerance)
  // of a reference-line point, which lies within half a sample spacing (<= 0.5 m) of a sample.
  constexpr double kMargin = 0.5 + 1e-3 + 0.05;
  constexpr double kMaxReach = 200.0;  // m: wider "lanes" are listed everywhere, not gridded
  for (std::size_t i = 0; i < roads.size(); ++i) {
    const auto index = static_cast<std::uint32_t>(i);
    const double reach = lateral_reach(roads[i]) + kMargin;
    const std::vector<Box>& leaves = roads[i].plan_view.samples().leaf_boxes();
    bool finite = std::isfinite(reach) && reach <= kMaxReach && !leaves.empty();
    for (const Box& b : leaves)
      finite = finite && std::isfinite(b.min_x) && std::isfinite(b.min_y) && std::isfinite(b.max_x) &&
               std::isfinite(b.max_y) && std::abs(b.min_x) < 1e9 && std::abs(b.max_x) < 1e9 &&
               std::abs(b.min_y) < 1e9 && std::abs(b.max_y) < 1e9;
    if (!finite) {
      everywhere_.push_back(index);
      continue;
    }
    for (const Box& b : leaves)
      for (std::int64_t cx = cell_of(b.min_x - reach); cx <= cell_of(b.max_x + reach); ++cx)
        for (std::int64_t cy = cell_of(b.min_y - reach); cy <= cell_of(b.max_y + reach); ++cy) {
          std::vector<std::uint32_t>& list = cells_[key(cx, cy)];
          if (list.empty() || list.back() != index) list.push_back(index);  // roads come in order
        }
  }
}

std::vector<std::uint32_t> RoadGrid::candidates(double x, double y) const {
  std::vector<std::uint32_t> out;
  if (std::isfinite(x) && std::isfinite(y)) {
    const auto it = cells_.find(key(cell_of(x), cell_of(y)));
    if (it != cells_.end()) out = it->second;
  }
  if (!everywhere_.empty()) {
    std::vector<std::uint32_t> merged;
    std::merge(out.begin(), out.end(), everywhere_.begin(), everywhere_.end(), std::back_inserter(merged));
    out = std::move(merged);
  }
  return out;
}

}  // namespace orch::opendrive
