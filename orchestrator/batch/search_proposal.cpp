#include "batch/search_proposal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "batch/gaussian_process.hpp"

namespace orch::batch {

namespace {

constexpr double kStraddleZ = 1.96;

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

std::vector<double> labels(const std::vector<bool>& pass) {
  std::vector<double> y;
  for (bool p : pass) y.push_back(p ? 1.0 : -1.0);
  return y;
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

std::vector<Proposal> propose_boundary(const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t count,
                                       SearchRng& rng, const SnapPoint& snap) {
  // Steps around the midpoints of the closest pass/fail pairs follow the boundary found so far.
  std::vector<std::pair<double, Point>> pairs;
  for (std::size_t i = 0; i < x.size(); ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    std::size_t other = x.size();
    for (std::size_t j = 0; j < x.size(); ++j)
      if (pass[j] != pass[i] && squared_distance(x[i], x[j]) < nearest) {
        nearest = squared_distance(x[i], x[j]);
        other = j;
      }
    if (other == x.size()) continue;
    Point mid(x[i].size());
    for (std::size_t d = 0; d < mid.size(); ++d) mid[d] = 0.5 * (x[i][d] + x[other][d]);
    pairs.emplace_back(nearest, mid);
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Point> centres;
  for (std::size_t i = 0; i < std::min<std::size_t>(10, pairs.size()); ++i) centres.push_back(pairs[i].second);
  return believer_batch(
      x, labels(pass), count, centres, rng, snap, "straddle",
      [](const GaussianProcess&, const GpPrediction& p, const std::vector<double>&) {
        return kStraddleZ * std::sqrt(p.variance) - std::abs(p.mean);
      },
      [](const GpPrediction& p) { return p.mean; });
}

BoundaryEstimate estimate_boundary(const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t levels) {
  BoundaryEstimate out;
  const std::size_t dims = x.front().size();
  std::size_t per_dim = std::max<std::size_t>(2, levels);
  while (per_dim > 2 && std::pow(static_cast<double>(per_dim), static_cast<double>(dims)) > 20000) --per_dim;
  out.levels = per_dim;
  std::size_t total = 1;
  for (std::size_t j = 0; j < dims; ++j) total *= per_dim;
  const GaussianProcess gp = GaussianProcess::fit(x, labels(pass));
  std::size_t uncertain = 0, passing = 0;
  for (std::size_t index = 0; index < total; ++index) {
    Point p(dims);
    std::size_t rest = index;
    for (std::size_t j = dims; j-- > 0;) {
      p[j] = static_cast<double>(rest % per_dim) / static_cast<double>(per_dim - 1);
      rest /= per_dim;
    }
    const GpPrediction pr = gp.predict(p);
    const bool ok = pr.mean >= 0;
    if (std::abs(pr.mean) < kStraddleZ * std::sqrt(pr.variance)) ++uncertain;
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
