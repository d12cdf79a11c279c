#include "batch/search_proposal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include "batch/gaussian_process.hpp"

namespace orch::batch {

namespace {

double squared_distance(const Point& a, const Point& b) {
  double s = 0;
  for (std::size_t j = 0; j < a.size(); ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return s;
}

bool already_there(const std::vector<Point>& points, const Point& p) {
  return std::any_of(points.begin(), points.end(), [&](const Point& q) { return squared_distance(p, q) < 1e-12; });
}

Point clamp_unit(Point p) {
  for (double& v : p) v = std::clamp(v, 0.0, 1.0);
  return p;
}

// Candidate points for maximising an acquisition: uniform ones over the cube and Gaussian
// steps around `centres` (two scales), snapped, none where a run already is.
std::vector<Point> candidates(std::size_t dims, const std::vector<Point>& centres, const std::vector<Point>& taken,
                              SearchRng& rng, const SnapPoint& snap) {
  std::vector<Point> out;
  const std::size_t uniform = std::min<std::size_t>(4000, 600 * dims);
  for (std::size_t i = 0; i < uniform; ++i) {
    Point p(dims);
    for (double& v : p) v = rng.uniform();
    out.push_back(snap(p));
  }
  for (const Point& c : centres)
    for (double scale : {0.08, 0.02})
      for (int i = 0; i < 60; ++i) {
        Point p = c;
        for (double& v : p) v += scale * rng.normal();
        out.push_back(snap(clamp_unit(p)));
      }
  std::vector<Point> fresh;
  for (auto& p : out)
    if (!already_there(taken, p)) fresh.push_back(std::move(p));
  return fresh;
}

// Chooses `count` points one after the other; after each, the model is refitted with the
// chosen point "believed" to give `believe(prediction)` (hyperparameters kept).
template <typename Score, typename Believe>
std::vector<Proposal> believer_batch(std::vector<Point> x, std::vector<double> y, std::size_t count,
                                     const std::vector<Point>& centres, SearchRng& rng, const SnapPoint& snap,
                                     const char* why, Score score, Believe believe) {
  std::vector<Proposal> out;
  const std::size_t dims = x.front().size();
  GaussianProcess gp = GaussianProcess::fit(x, y);
  const GpHyper hyper = gp.hyper();
  std::vector<Point> pool = candidates(dims, centres, x, rng, snap);
  for (std::size_t k = 0; k < count; ++k) {
    double best_score = -std::numeric_limits<double>::infinity();
    std::size_t best = pool.size();
    for (std::size_t i = 0; i < pool.size(); ++i) {
      if (already_there(x, pool[i])) continue;
      const double s = score(gp, gp.predict(pool[i]), y);
      if (s > best_score) {
        best_score = s;
        best = i;
      }
    }
    Point chosen;
    if (best == pool.size()) {  // every candidate taken (a small discrete space): any free point
      Point p(dims);
      for (double& v : p) v = rng.uniform();
      chosen = snap(p);
      best_score = 0;
    } else {
      chosen = pool[best];
    }
    out.push_back(Proposal{chosen, best_score, why});
    y.push_back(believe(gp.predict(chosen)));
    x.push_back(chosen);
    gp = GaussianProcess::fit_with(x, y, hyper);
  }
  return out;
}


}  // namespace

std::uint64_t SearchRng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double SearchRng::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double SearchRng::normal() {
  const double u1 = 1.0 - uniform();  // (0, 1]
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::vector<Proposal> latin_hypercube(std::size_t n, std::size_t dims, SearchRng& rng, const SnapPoint& snap) {
  std::vector<Proposal> out(n, Proposal{Point(dims), 0, "latin hypercube"});
  for (std::size_t j = 0; j < dims; ++j) {
    std::vector<std::size_t> slice(n);
    for (std::size_t i = 0; i < n; ++i) slice[i] = i;
    for (std::size_t i = n; i > 1; --i) std::swap(slice[i - 1], slice[rng.next() % i]);  // Fisher-Yates
    for (std::size_t i = 0; i < n; ++i) out[i].point[j] = (static_cast<double>(slice[i]) + rng.uniform()) / static_cast<double>(n);
  }
  for (auto& p : out) p.point = snap(p.point);
  return out;
}

std::vector<Proposal> uniform_random(std::size_t n, std::size_t dims, SearchRng& rng, const SnapPoint& snap) {
  std::vector<Proposal> out;
  for (std::size_t i = 0; i < n; ++i) {
    Point p(dims);
    for (double& v : p) v = rng.uniform();
    out.push_back(Proposal{snap(p), 0, "uniform random"});
  }
  return out;
}

std::size_t grid_levels(std::size_t budget, std::size_t dims) {
  auto k = static_cast<std::size_t>(std::floor(std::pow(static_cast<double>(budget), 1.0 / static_cast<double>(dims)) + 1e-9));
  return std::max<std::size_t>(k, 2);
}

std::vector<Proposal> grid_points(std::size_t budget, std::size_t dims, std::size_t first, std::size_t n) {
  const std::size_t k = grid_levels(budget, dims);
  std::size_t total = 1;
  for (std::size_t j = 0; j < dims; ++j) total *= k;
  std::vector<Proposal> out;
  for (std::size_t index = first; index < std::min(total, first + n); ++index) {
    Point p(dims);
    std::size_t rest = index;
    for (std::size_t j = dims; j-- > 0;) {  // the last dimension varies fastest
      p[j] = static_cast<double>(rest % k) / static_cast<double>(k - 1);
      rest /= k;
    }
    out.push_back(Proposal{p, 0, "grid"});
  }
  return out;
}

std::vector<Proposal> propose_minimum(const std::vector<Point>& x, const std::vector<double>& y, std::size_t count,
                                      SearchRng& rng, const SnapPoint& snap) {
  // Steps around the few best runs so far refine the minimum; uniform candidates explore.
  std::vector<std::size_t> order(x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return y[a] < y[b]; });
  std::vector<Point> centres;
  for (std::size_t i = 0; i < std::min<std::size_t>(5, order.size()); ++i) centres.push_back(x[order[i]]);
  const double best = y[order.front()];
  return believer_batch(
      x, y, count, centres, rng, snap, "expected improvement",
      [best](const GaussianProcess&, const GpPrediction& p, const std::vector<double>&) { return expected_improvement(p, best); },
      [](const GpPrediction& p) { return p.mean; });
}

namespace {

// The boundary's sparse grid: level-0 cells of 1/n0 per dimension; a cell whose corners
// disagree (some pass, some fail) is split in 2^d children down to `min_cell`. A point's key
// is its coordinates on a fine lattice, so corners shared by cells are run once.
using Key = std::vector<long long>;
Key key_of(const Point& p) {
  Key k;
  for (double v : p) k.push_back(std::llround(v * 1048576.0));
  return k;
}

struct Cell {
  Point lower;
  double size = 1;
};

std::size_t initial_cells(std::size_t dims) { return dims <= 2 ? 4 : 2; }

std::vector<Point> corners(const Cell& c, const SnapPoint& snap) {
  const std::size_t d = c.lower.size();
  std::vector<Point> out;
  for (std::size_t bits = 0; bits < (std::size_t{1} << d); ++bits) {
    Point p = c.lower;
    for (std::size_t j = 0; j < d; ++j)
      if (bits & (std::size_t{1} << j)) p[j] = std::min(1.0, p[j] + c.size);
    out.push_back(snap(p));
  }
  return out;
}

std::vector<Cell> level0(std::size_t dims) {
  const std::size_t n = initial_cells(dims);
  std::size_t total = 1;
  for (std::size_t j = 0; j < dims; ++j) total *= n;
  std::vector<Cell> out;
  for (std::size_t index = 0; index < total; ++index) {
    Cell c{Point(dims), 1.0 / static_cast<double>(n)};
    std::size_t rest = index;
    for (std::size_t j = dims; j-- > 0;) {
      c.lower[j] = static_cast<double>(rest % n) * c.size;
      rest /= n;
    }
    out.push_back(c);
  }
  return out;
}

std::vector<Cell> children(const Cell& c) {
  const std::size_t d = c.lower.size();
  std::vector<Cell> out;
  for (std::size_t bits = 0; bits < (std::size_t{1} << d); ++bits) {
    Cell child{c.lower, c.size / 2};
    for (std::size_t j = 0; j < d; ++j)
      if (bits & (std::size_t{1} << j)) child.lower[j] += child.size;
    out.push_back(child);
  }
  return out;
}

struct Known {
  std::map<Key, bool> pass;
  // -1 a corner not run, 0 all agree, 1 they disagree
  int state(const Cell& c, const SnapPoint& snap) const {
    bool any_pass = false, any_fail = false;
    for (const auto& p : corners(c, snap)) {
      const auto it = pass.find(key_of(p));
      if (it == pass.end()) return -1;
      (it->second ? any_pass : any_fail) = true;
    }
    return any_pass && any_fail ? 1 : 0;
  }
};

Known known_of(const std::vector<Point>& x, const std::vector<bool>& pass) {
  Known k;
  for (std::size_t i = 0; i < x.size(); ++i) k.pass[key_of(x[i])] = pass[i];
  return k;
}

bool contains(const Cell& c, const Point& p) {
  for (std::size_t j = 0; j < p.size(); ++j)
    if (p[j] < c.lower[j] - 1e-12 || p[j] > c.lower[j] + c.size + 1e-12) return false;
  return true;
}

}  // namespace

std::vector<Proposal> propose_boundary(std::size_t dims, const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t count,
                                       double min_cell, const SnapPoint& snap) {
  const Known known = known_of(x, pass);
  std::vector<Cell> cells = level0(dims);
  for (int level = 0; !cells.empty(); ++level) {
    std::vector<Proposal> missing;
    std::set<Key> seen;
    for (const Cell& c : cells)
      for (const auto& p : corners(c, snap))
        if (!known.pass.count(key_of(p)) && seen.insert(key_of(p)).second && missing.size() < count)
          missing.push_back(Proposal{p, c.size,
                                     level == 0 ? "initial grid" : "refine a cell whose corners disagree"});
    if (!missing.empty()) return missing;
    std::vector<Cell> next;
    for (const Cell& c : cells)
      if (c.size / 2 >= min_cell - 1e-12 && known.state(c, snap) == 1)
        for (auto& child : children(c)) next.push_back(std::move(child));
    cells = std::move(next);
  }
  return {};  // the boundary is resolved to min_cell
}

namespace {

// The evaluation lattice of a boundary estimate: `levels` points a dimension in the unit
// box (fewer when that would exceed 20,000 points), in index order.
std::vector<Point> estimate_lattice(std::size_t dims, std::size_t levels, std::size_t& per_dim) {
  per_dim = std::max<std::size_t>(2, levels);
  while (per_dim > 2 && std::pow(static_cast<double>(per_dim), static_cast<double>(dims)) > 20000) --per_dim;
  std::size_t total = 1;
  for (std::size_t j = 0; j < dims; ++j) total *= per_dim;
  std::vector<Point> lattice;
  lattice.reserve(total);
  for (std::size_t index = 0; index < total; ++index) {
    Point p(dims);
    std::size_t rest = index;
    for (std::size_t j = dims; j-- > 0;) {
      p[j] = static_cast<double>(rest % per_dim) / static_cast<double>(per_dim - 1);
      rest /= per_dim;
    }
    lattice.push_back(std::move(p));
  }
  return lattice;
}

}  // namespace

BoundaryEstimate estimate_boundary(const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t levels,
                                   const SnapPoint& snap) {
  BoundaryEstimate out;
  const std::size_t dims = x.front().size();
  std::vector<Point> lattice = estimate_lattice(dims, levels, out.levels);
  const std::size_t total = lattice.size();
  const Known known = known_of(x, pass);
  const std::vector<Cell> roots = level0(dims);
  std::size_t uncertain = 0, passing = 0;
  for (Point& p : lattice) {
    // The smallest cell holding p whose corners were all run.
    Cell leaf = *std::find_if(roots.begin(), roots.end(), [&](const Cell& c) { return contains(c, p); });
    while (known.state(leaf, snap) == 1) {
      bool deeper = false;
      for (const Cell& child : children(leaf))
        if (contains(child, p) && known.state(child, snap) >= 0) {
          leaf = child;
          deeper = true;
          break;
        }
      if (!deeper) break;
    }
    // Multilinear interpolation of the corners' +1 (pass) / -1 (fail): the sign classifies.
    double value = 0, weight_sum = 0;
    const std::vector<Point> cs = corners(leaf, [](const Point& q) { return q; });
    const std::vector<Point> snapped = corners(leaf, snap);
    for (std::size_t k = 0; k < cs.size(); ++k) {
      double w = 1;
      for (std::size_t j = 0; j < dims; ++j) {
        const double t = std::clamp((p[j] - leaf.lower[j]) / leaf.size, 0.0, 1.0);
        w *= cs[k][j] > leaf.lower[j] + 1e-12 ? t : 1 - t;
      }
      const auto it = known.pass.find(key_of(snapped[k]));
      if (it == known.pass.end()) continue;
      value += w * (it->second ? 1.0 : -1.0);
      weight_sum += w;
    }
    const double mean = weight_sum > 0 ? value / weight_sum : 0.0;
    const bool ok = mean >= 0;
    if (known.state(leaf, snap) != 0) ++uncertain;
    if (ok) ++passing;
    out.lattice.push_back(std::move(p));
    out.pass.push_back(ok);
    out.mean.push_back(mean);
  }
  out.uncertain_fraction = static_cast<double>(uncertain) / static_cast<double>(total);
  out.pass_fraction = static_cast<double>(passing) / static_cast<double>(total);
  return out;
}

BoundaryEstimate estimate_boundary_gp(const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t levels) {
  BoundaryEstimate out;
  std::vector<Point> lattice = estimate_lattice(x.front().size(), levels, out.levels);
  const std::size_t total = lattice.size();
  const GaussianProcess gp = GaussianProcess::fit(x, [&] {
    std::vector<double> y;
    for (bool p : pass) y.push_back(p ? 1.0 : -1.0);
    return y;
  }());
  std::size_t uncertain = 0, passing = 0;
  for (Point& p : lattice) {
    const GpPrediction pr = gp.predict(p);
    const bool ok = pr.mean >= 0;
    if (std::abs(pr.mean) < 1.96 * std::sqrt(pr.variance)) ++uncertain;
    if (ok) ++passing;
    out.lattice.push_back(std::move(p));
    out.pass.push_back(ok);
    out.mean.push_back(pr.mean);
  }
  out.uncertain_fraction = static_cast<double>(uncertain) / static_cast<double>(total);
  out.pass_fraction = static_cast<double>(passing) / static_cast<double>(total);
  return out;
}

}  // namespace orch::batch
