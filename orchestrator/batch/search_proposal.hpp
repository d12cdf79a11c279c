#pragma once
// The pure logic of `orchestrator search` (docs/search.md): where to run next, given the
// points run so far (unit-cube coordinates) and what they gave. No files, no runs: the
// search runner (search_runner.hpp) maps points to parameter values and back.
//  - an initial Latin hypercube,
//  - falsification: a pattern search around the best run alternating with expected
//    improvement of a Gaussian process (gaussian_process.hpp),
//    (a batch of J points per iteration by the "kriging believer": each chosen point is
//    added with its predicted value before the next is chosen),
//  - boundary: adaptive refinement of a sparse grid: a coarse grid, then every cell whose
//    corners disagree (some pass, some fail) is split, level by level, down to a stated
//    cell size (docs/search.md has the measurements that chose it over a Gaussian-process
//    classifier with straddle sampling),
//  - uniform random and full-factorial grid proposals, the baselines of the proof.
// Every proposal is a pure function of its inputs and the seed.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace orch::batch {

using Point = std::vector<double>;

// A deterministic random source (splitmix64): the same numbers on every platform, unlike the
// standard library's distributions. The seed is mixed first: splitmix's state advances by a
// constant, so seeding it with a multiple of that constant made seed s + 1's numbers those of
// seed s shifted by one draw (nearly the same candidates, nearly the same search).
class SearchRng {
 public:
  explicit SearchRng(std::uint64_t seed) : state_(mix(seed ^ 0x632BE59BD9B4E019ULL)) {}
  std::uint64_t next();
  double uniform();  // [0, 1)
  double normal();   // standard normal

 private:
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

// Snaps a unit-cube point to what the parameters can take (whole numbers, choices).
using SnapPoint = std::function<Point(const Point&)>;

struct Proposal {
  Point point;
  double acquisition = 0;  // the acquisition value it was chosen for (0 for designs)
  std::string why;         // "latin hypercube", "expected improvement", ...
};

// `n` points, one in each of n equal slices of every dimension.
std::vector<Proposal> latin_hypercube(std::size_t n, std::size_t dims, SearchRng& rng, const SnapPoint& snap);
std::vector<Proposal> uniform_random(std::size_t n, std::size_t dims, SearchRng& rng, const SnapPoint& snap);
// The first `n` of the full-factorial grid with k = floor(budget^(1/dims)) levels per
// dimension (cell centres included at both ends), starting at grid index `first`.
std::vector<Proposal> grid_points(std::size_t budget, std::size_t dims, std::size_t first, std::size_t n);
std::size_t grid_levels(std::size_t budget, std::size_t dims);

// The first runs of a falsification: the 2^d corners of the box (d <= 3; criticality is
// often monotone in the parameters, so the extremes come first), filled up with a Latin
// hypercube to `n`; initial_design_size: how many (at least `jobs`).
std::vector<Proposal> initial_design(std::size_t n, std::size_t dims, SearchRng& rng, const SnapPoint& snap);
std::size_t initial_design_size(std::size_t dims, std::size_t jobs);
// `count` points: every other iteration (the first after the initial design) a pattern
// search's poll around the best run, the others the largest expected improvement below the
// smallest of `y` over the box (filled up with it when the poll has fewer points).
std::vector<Proposal> propose_minimum(const std::vector<Point>& x, const std::vector<double>& y, std::size_t count,
                                      SearchRng& rng, const SnapPoint& snap);
// Up to `count` corners the sparse grid needs next (`pass[i]` is the outcome of x[i]), the
// coarsest level first; none when every disagreeing cell is down to `min_cell` (the
// boundary is resolved). Proposals carry the cell size as their acquisition value.
std::vector<Proposal> propose_boundary(std::size_t dims, const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t count,
                                       double min_cell, const SnapPoint& snap);

// The boundary as estimated from the runs: pass/fail on a lattice of the unit cube (`levels`
// points per dimension, at most ~20000 in all) by multilinear interpolation of +1/-1 in the
// smallest run cell holding each point; uncertain: in a cell whose corners disagree.
struct BoundaryEstimate {
  std::size_t levels = 0;
  std::vector<Point> lattice;
  std::vector<bool> pass;
  std::vector<double> mean;
  double uncertain_fraction = 0;
  double pass_fraction = 0;
};
BoundaryEstimate estimate_boundary(const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t levels,
                                   const SnapPoint& snap);
// The same from scattered runs (uniform random sampling): the sign of a Gaussian process
// fitted to +1/-1; uncertain where |mean| < 1.96 sigma.
BoundaryEstimate estimate_boundary_gp(const std::vector<Point>& x, const std::vector<bool>& pass, std::size_t levels);

}  // namespace orch::batch
