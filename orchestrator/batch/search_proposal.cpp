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
  // Points on the faces of the box: criticality is often monotone in a parameter (harder
  // braking, a shorter gap), so minima lie on the faces, where uniform candidates never are.
  for (std::size_t i = 0; i < uniform / 4; ++i) {
    Point p(dims);
    for (double& v : p) v = rng.uniform();
    p[rng.next() % dims] = static_cast<double>(rng.next() % 2);
    out.push_back(snap(p));
  }
  std::vector<Point> fresh;
  for (auto& p : out)
    if (!already_there(taken, p)) fresh.push_back(std::move(p));
  return fresh;
}

// The poll of a pattern search around the incumbent `c`: c +- step along each coordinate
// (clamped to the box), at the largest step of 1/4, 1/8, ... of the range that still has a
// point not run. An improvement moves the incumbent and the poll starts again at 1/4; a
// poll with every point run and none better halves the step. A pure function of the runs.
std::vector<Point> poll_points(const Point& c, const std::vector<Point>& taken, const SnapPoint& snap, double& step) {
  for (step = 0.25; step > 1.0 / 1024; step /= 2) {
    std::vector<Point> out;
    for (std::size_t j = 0; j < c.size(); ++j)
      for (double sign : {-1.0, 1.0}) {
        Point p = c;
        p[j] += sign * step;
        p = snap(clamp_unit(p));
        if (!already_there(taken, p) && !already_there(out, p)) out.push_back(std::move(p));
      }
    if (!out.empty()) return out;
  }
  return {};
}

// The best-scoring candidate of `pool` not yet in `x` (pool.size() when none is free).
template <typename Score>
std::size_t best_candidate(const std::vector<Point>& pool, const std::vector<Point>& x, Score score, double& best_score) {
  best_score = -std::numeric_limits<double>::infinity();
  std::size_t best = pool.size();
  for (std::size_t i = 0; i < pool.size(); ++i) {
    if (already_there(x, pool[i])) continue;
    const double s = score(pool[i]);
    if (s > best_score) {
      best_score = s;
      best = i;
    }
  }
  return best;
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

std::vector<Proposal> propose_minimum(const std::vector<Point>& x0, const std::vector<double>& y0, std::size_t count,
                                      SearchRng& rng, const SnapPoint& snap) {
  // Two kinds of iterations, alternating: exploitation, a pattern search's poll around the
  // best run so far (the poll's points ordered by the model's mean: exploration is the other
  // kind's job), which refines a minimum once one is in sight; and exploration, the largest
  // expected improvement over the whole box. Whole iterations rather than points alternate
  // (a parallel poll: the directions of one poll run side by side), and the first after the
  // initial design is a poll: after the corners the model knows little, and the poll walks
  // along the faces from the best corner, where monotone objectives have their minimum (on
  // the analytic tests of test_search_logic.cpp a face minimum is found in 5 runs instead
  // of 6; docs/search.md). The poll's points not needed fill up with exploration. The batch
  // is built by the "kriging believer": each chosen point is added with its predicted mean
  // (the hyperparameters of the first fit kept) before the next is chosen, and that mean
  // lowers the best value expected improvement is measured from (without it a batch's second
  // point sat next to its first: the believed point still promised the same improvement).
  std::vector<Point> x = x0;
  std::vector<double> y = y0;
  const std::size_t dims = x.front().size();
  const std::size_t incumbent = static_cast<std::size_t>(std::min_element(y0.begin(), y0.end()) - y0.begin());
  double best = y0[incumbent];
  GaussianProcess gp = GaussianProcess::fit(x, y);
  const GpHyper hyper = gp.hyper();
  const std::vector<Point> global = candidates(dims, {x0[incumbent]}, x, rng, snap);
  double step = 0;
  const std::vector<Point> local = poll_points(x0[incumbent], x, snap, step);
  const bool poll_iteration = (x0.size() / count) % 2 == 0;  // a pure function of the runs
  std::vector<Proposal> out;
  for (std::size_t k = 0; k < count; ++k) {
    double score = 0;
    std::size_t i = local.size();
    if (poll_iteration)
      i = best_candidate(local, x, [&](const Point& p) { return -gp.predict(p).mean; }, score);
    const bool exploit = i < local.size();  // else the poll is exhausted by this batch: explore
    const std::vector<Point>& pool = exploit ? local : global;
    if (!exploit)
      i = best_candidate(pool, x, [&](const Point& p) { return expected_improvement(gp.predict(p), best); }, score);
    Point chosen;
    if (i == pool.size()) {  // every candidate taken (a small discrete space): any free point
      Point p(dims);
      for (double& v : p) v = rng.uniform();
      chosen = snap(p);
      score = 0;
    } else {
      chosen = pool[i];
    }
    out.push_back(exploit ? Proposal{chosen, step, "pattern search around the best"}
                          : Proposal{chosen, score, "expected improvement"});
    y.push_back(gp.predict(chosen).mean);
    best = std::min(best, y.back());
    x.push_back(chosen);
    gp = GaussianProcess::fit_with(x, y, hyper);
  }
  return out;
}

std::vector<Proposal> initial_design(std::size_t n, std::size_t dims, SearchRng& rng, const SnapPoint& snap) {
  std::vector<Proposal> out;
  if (dims <= 3)
    for (std::size_t bits = 0; bits < (std::size_t{1} << dims) && out.size() < n; ++bits) {
      Point p(dims);
      for (std::size_t j = 0; j < dims; ++j) p[j] = (bits >> j) & 1U ? 1.0 : 0.0;
      out.push_back(Proposal{snap(p), 0, "corner of the box"});
    }
  if (out.size() < n)
    for (auto& p : latin_hypercube(n - out.size(), dims, rng, snap)) out.push_back(std::move(p));
  return out;
}

std::size_t initial_design_size(std::size_t dims, std::size_t jobs) {
  return std::max(jobs, dims <= 3 ? std::size_t{1} << dims : dims + 1);
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

std::size_t initial_cells(std::size_t dims) { return dims <= 3 ? 2 : 1; }

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

// The points a disagreeing cell's children need, other than its corners: the 3^d lattice of
// half steps. A point in the interior of a face (an edge, a side) whose corners all agree
// gets their outcome without a run: the boundary crosses the faces whose corners disagree,
// so only those are bisected (one run per crossing edge and halving, plus the centre) and a
// cell costs about 3 runs in two dimensions instead of 5. The price: a failing island that
// touches a face without reaching its corners is missed (as a coarse grid misses it).
void infer_half_points(const Cell& c, Known& known, const SnapPoint& snap) {
  const std::size_t d = c.lower.size();
  std::size_t total = 1;
  for (std::size_t j = 0; j < d; ++j) total *= 3;
  for (std::size_t index = 0; index < total; ++index) {
    Point p = c.lower;
    std::vector<std::size_t> free_dims;
    std::size_t rest = index;
    for (std::size_t j = 0; j < d; ++j, rest /= 3) {
      const std::size_t t = rest % 3;
      p[j] = std::min(1.0, c.lower[j] + static_cast<double>(t) * c.size / 2);
      if (t == 1) free_dims.push_back(j);
    }
    if (free_dims.empty() || free_dims.size() == d) continue;  // a corner, or the centre (always run)
    const Key key = key_of(snap(p));
    if (known.pass.count(key)) continue;
    bool any_pass = false, any_fail = false, all_known = true;
    for (std::size_t bits = 0; bits < (std::size_t{1} << free_dims.size()) && all_known; ++bits) {
      Point q = p;
      for (std::size_t f = 0; f < free_dims.size(); ++f)
        q[free_dims[f]] = std::min(1.0, c.lower[free_dims[f]] + ((bits >> f) & 1U ? c.size : 0.0));
      const auto it = known.pass.find(key_of(snap(q)));
      if (it == known.pass.end()) all_known = false;
      else (it->second ? any_pass : any_fail) = true;
    }
    if (all_known && any_pass != any_fail) known.pass[key] = any_pass;
  }
}

// The runs' outcomes, completed with what the refinement infers (above), walking the same
// cells as propose_boundary: the level-0 grid, then the children of every disagreeing cell
// of at least 2 * min_cell.
Known known_of(std::size_t dims, const std::vector<Point>& x, const std::vector<bool>& pass, double min_cell,
               const SnapPoint& snap) {
  Known k;
  for (std::size_t i = 0; i < x.size(); ++i) k.pass[key_of(x[i])] = pass[i];
  std::vector<Cell> cells = level0(dims);
  while (!cells.empty()) {
    std::vector<Cell> next;
    for (const Cell& c : cells)
      if (c.size / 2 >= min_cell - 1e-12 && k.state(c, snap) == 1) {
        infer_half_points(c, k, snap);
        for (auto& child : children(c)) next.push_back(std::move(child));
      }
    cells = std::move(next);
  }
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
  const Known known = known_of(dims, x, pass, min_cell, snap);
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
  const Known known = known_of(dims, x, pass, 0.0, snap);
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
