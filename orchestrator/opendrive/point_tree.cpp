#include "opendrive/point_tree.hpp"

#include <algorithm>
#include <limits>

namespace orch::opendrive {

double Box::distance2(double x, double y) const {
  // Rounding is monotonic, so each difference is at most the one to any point inside.
  const double dx = x < min_x ? x - min_x : (x > max_x ? x - max_x : 0.0);
  const double dy = y < min_y ? y - min_y : (y > max_y ? y - max_y : 0.0);
  return dx * dx + dy * dy;
}

void Box::add(const Box& other) {
  min_x = std::min(min_x, other.min_x);
  min_y = std::min(min_y, other.min_y);
  max_x = std::max(max_x, other.max_x);
  max_y = std::max(max_y, other.max_y);
}

PointTree::PointTree(std::vector<double> xs, std::vector<double> ys) : xs_(std::move(xs)), ys_(std::move(ys)) {
  ys_.resize(xs_.size());
  if (xs_.empty()) return;
  std::vector<Box> leaves;
  for (std::size_t first = 0; first < xs_.size(); first += kLeaf) {
    Box b{xs_[first], ys_[first], xs_[first], ys_[first]};
    for (std::size_t i = first + 1; i < std::min(xs_.size(), first + kLeaf); ++i) b.add({xs_[i], ys_[i], xs_[i], ys_[i]});
    leaves.push_back(b);
  }
  levels_.push_back(std::move(leaves));
  while (levels_.back().size() > 1) {
    const std::vector<Box>& below = levels_.back();
    std::vector<Box> above;
    for (std::size_t i = 0; i < below.size(); i += 2) {
      Box b = below[i];
      if (i + 1 < below.size()) b.add(below[i + 1]);
      above.push_back(b);
    }
    levels_.push_back(std::move(above));
  }
}

const std::vector<Box>& PointTree::leaf_boxes() const {
  static const std::vector<Box> kNone;
  return levels_.empty() ? kNone : levels_.front();
}

void PointTree::visit(std::size_t level, std::size_t k, double x, double y, double& best_d2, std::size_t& best) const {
  // Boxes exactly as far as the best so far are still searched: they may hold an equally
  // near point with a lower index.
  if (levels_[level][k].distance2(x, y) > best_d2) return;
  if (level == 0) {
    const std::size_t end = std::min(xs_.size(), (k + 1) * kLeaf);
    for (std::size_t i = k * kLeaf; i < end; ++i) {
      const double d2 = (x - xs_[i]) * (x - xs_[i]) + (y - ys_[i]) * (y - ys_[i]);
      if (d2 < best_d2 || (d2 == best_d2 && i < best)) best_d2 = d2, best = i;
    }
    return;
  }
  const std::vector<Box>& below = levels_[level - 1];
  const std::size_t a = 2 * k;
  const std::size_t b = a + 1;
  if (b >= below.size()) {
    visit(level - 1, a, x, y, best_d2, best);
    return;
  }
  // The nearer child first, so the farther one is usually skipped.
  if (below[b].distance2(x, y) < below[a].distance2(x, y)) {
    visit(level - 1, b, x, y, best_d2, best);
    visit(level - 1, a, x, y, best_d2, best);
  } else {
    visit(level - 1, a, x, y, best_d2, best);
    visit(level - 1, b, x, y, best_d2, best);
  }
}

std::size_t PointTree::nearest(double x, double y) const {
  if (levels_.empty()) return 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  std::size_t best = std::numeric_limits<std::size_t>::max();
  visit(levels_.size() - 1, 0, x, y, best_d2, best);
  return best == std::numeric_limits<std::size_t>::max() ? 0 : best;
}

}  // namespace orch::opendrive
