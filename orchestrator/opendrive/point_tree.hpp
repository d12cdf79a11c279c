#pragma once
// The nearest of a sequence of points (a road's reference line sampled about every metre),
// found in O(log n) instead of by walking every point: consecutive points are grouped into
// leaves of kLeaf, each with its bounding box, and the boxes are merged pairwise, level by
// level, into a tree. The search skips every box farther than the nearest point found so
// far, so it returns exactly what a walk over all points keeping the first strict minimum
// returns (the lowest index among equally near points).
#include <cstddef>
#include <vector>

namespace orch::opendrive {

struct Box {
  double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;
  // Squared distance from (x, y) to the box (0 inside); never more than the squared
  // distance, computed the same way, to any point inside the box.
  [[nodiscard]] double distance2(double x, double y) const;
  void add(const Box& other);
};

class PointTree {
 public:
  static constexpr std::size_t kLeaf = 8;

  PointTree() = default;
  PointTree(std::vector<double> xs, std::vector<double> ys);
  [[nodiscard]] std::size_t size() const { return xs_.size(); }
  // Index of the nearest point (0 when there are none or (x, y) is not a number).
  [[nodiscard]] std::size_t nearest(double x, double y) const;
  // The boxes of the leaves: points kLeaf * i ... kLeaf * (i + 1) - 1.
  [[nodiscard]] const std::vector<Box>& leaf_boxes() const;

 private:
  void visit(std::size_t level, std::size_t k, double x, double y, double& best_d2, std::size_t& best) const;
  std::vector<double> xs_, ys_;
  std::vector<std::vector<Box>> levels_;  // [0] the leaves; each next level pairs the one below; last: one box
};

}  // namespace orch::opendrive
