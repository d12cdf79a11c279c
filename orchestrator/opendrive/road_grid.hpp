#pragma once
// Which roads of a network can hold a point on one of their lanes, in O(1): a grid of square
// cells over the network, each listing the roads whose lanes may reach into it (the boxes of
// the road's reference-line samples, widened by the farthest any lane border can lie from
// the reference line). RoadNetwork::to_road projects the point onto these roads only, and
// onto every road only when none of them holds it on a lane.
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace orch::opendrive {

struct Road;

// An upper bound of |t| of any lane border of the road anywhere along it (the lane offset's
// largest magnitude plus, per side of each lane section, the sum of its lanes' largest widths).
double lateral_reach(const Road& road);

class RoadGrid {
 public:
  RoadGrid() = default;
  explicit RoadGrid(const std::vector<Road>& roads);
  // Indices into `roads`, ascending, of every road that may hold (x, y) on a lane.
  [[nodiscard]] std::vector<std::uint32_t> candidates(double x, double y) const;

 private:
  struct CellHash {
    std::size_t operator()(std::uint64_t key) const { return key * 0x9E3779B97F4A7C15ULL >> 17; }
  };
  static std::uint64_t key(std::int64_t cx, std::int64_t cy);
  [[nodiscard]] std::int64_t cell_of(double v) const;

  double cell_ = 32.0;  // m
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>, CellHash> cells_;
  std::vector<std::uint32_t> everywhere_;  // roads too wide to grid (absurd lane widths): always candidates
};

}  // namespace orch::opendrive
