#pragma once
// Union-find over indices 0..n-1: which items ended up joined, transitively. The root of a
// component is always its smallest index, so results do not depend on the order of joins.
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace orch {

class Components {
 public:
  explicit Components(std::size_t n = 0) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  // A new item in a component of its own; returns its index.
  std::size_t add() {
    parent_.push_back(parent_.size());
    return parent_.size() - 1;
  }
  std::size_t root(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    const std::size_t ra = root(a);
    const std::size_t rb = root(b);
    parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace orch
