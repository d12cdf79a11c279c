#include "metrics/pet.hpp"

#include <cmath>
#include <unordered_map>

#include "core/checked_numeric.hpp"


namespace orch::metrics {

namespace {

constexpr double kCell = 10.0;  // m, grid of path segments

long long cell_key(const Vec2& p) { return grid_cell(p.x(), kCell) * 1000003LL + grid_cell(p.y(), kCell); }

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The crossing point of segments p0-p1 and q0-q1, when they cross at more than kMinCrossing.
std::optional<Vec2> crossing(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  const Vec2 r = p1 - p0, s = q1 - q0;
  const double denom = cross(r, s);
  if (r.norm() == 0 || s.norm() == 0) return std::nullopt;
  if (std::abs(denom) < std::sin(kMinCrossing) * r.norm() * s.norm()) return std::nullopt;
  const double t = cross(q0 - p0, s) / denom;
  const double u = cross(q0 - p0, r) / denom;
  if (t < 0 || t > 1 || u < 0 || u > 1) return std::nullopt;
  return p0 + t * r;
}

struct Interval {
  double first = 0;
  double last = 0;
  bool any = false;
};

Interval occupancy(const std::vector<TrajectorySample>& tr, const Vec2& p) {
  Interval in;
  const sim::Box dot{p, 0, 0, 0};
  for (const auto& s : tr) {
    if (!sim::boxes_touch(s.box, dot)) continue;
    if (!in.any) in.first = s.time;
    in.last = s.time;
    in.any = true;
  }
  return in;
}

}  // namespace

PathCells::PathCells(const std::vector<TrajectorySample>& path) : path_(path) {
  // Segments are short (a step), so a segment is listed under the cells of its two ends.
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (path[i + 1].resumed) continue;
    cells_[cell_key(path[i].box.centre)].push_back(i);
    if (cell_key(path[i + 1].box.centre) != cell_key(path[i].box.centre)) cells_[cell_key(path[i + 1].box.centre)].push_back(i);
  }
}

const std::vector<std::size_t>* PathCells::at(const Vec2& p) const {
  const auto it = cells_.find(cell_key(p));
  return it == cells_.end() ? nullptr : &it->second;
}

std::optional<PetResult> post_encroachment_time(const std::vector<TrajectorySample>& a,
                                                const std::vector<TrajectorySample>& b) {
  return post_encroachment_time(PathCells(a), b);
}

std::optional<PetResult> post_encroachment_time(const PathCells& cells, const std::vector<TrajectorySample>& b) {
  const std::vector<TrajectorySample>& a = cells.path();
  if (a.size() < 2 || b.size() < 2) return std::nullopt;
  std::vector<Vec2> points;
  for (std::size_t j = 0; j + 1 < b.size(); ++j) {
    if (b[j + 1].resumed) continue;
    const Vec2& q0 = b[j].box.centre;
    const Vec2& q1 = b[j + 1].box.centre;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto* segments = cells.at(q0 + Vec2(dx * kCell, dy * kCell));
        if (!segments) continue;
        for (std::size_t i : *segments)
          if (auto p = crossing(a[i].box.centre, a[i + 1].box.centre, q0, q1)) points.push_back(*p);
      }
  }
  std::optional<PetResult> best;
  for (const Vec2& p : points) {
    const Interval ia = occupancy(a, p), ib = occupancy(b, p);
    if (!ia.any || !ib.any) continue;
    PetResult r;
    r.point = p;
    if (ia.first <= ib.last && ib.first <= ia.last) {
      r.pet = 0;
      r.time = std::max(ia.first, ib.first);
    } else if (ia.last < ib.first) {
      r.pet = ib.first - ia.last;
      r.time = ib.first;
    } else {
      r.pet = ia.first - ib.last;
      r.time = ia.first;
    }
    if (!best || r.pet < best->pet) best = r;
  }
  return best;
}

void append_sample(std::vector<TrajectorySample>& trajectory, const TrajectorySample& s, double min_move) {
  if (!trajectory.empty() && !s.resumed && (trajectory.back().box.centre - s.box.centre).norm() < min_move) {
    // Standing: keep the time the stop ends at, without a sample per step.
    if (trajectory.size() >= 2 &&
        (trajectory[trajectory.size() - 2].box.centre - trajectory.back().box.centre).norm() < min_move) {
      trajectory.back().time = s.time;
      return;
    }
    trajectory.push_back(s);
    return;
  }
  trajectory.push_back(s);
}

void TrajectoryBook::record(double time, const std::vector<Seen>& bodies) {
  ++step_;
  for (const auto& b : bodies) {
    Track& t = trajectories_[b.id];
    if (t.last_step == step_) continue;  // the same id twice in a step: the first counts
    const bool resumed = t.last_step >= 0 && t.last_step != step_ - 1;
    append_sample(t.samples, {time, b.box, resumed});
    t.last_step = step_;
  }
}

std::optional<PetWith> TrajectoryBook::min_pet(const std::string& id) const {
  const auto own = trajectories_.find(id);
  if (own == trajectories_.end()) return std::nullopt;
  std::optional<PetWith> best;
  const PathCells cells(own->second.samples);
  for (const auto& [other, track] : trajectories_) {
    if (other == id) continue;
    const auto pet = post_encroachment_time(cells, track.samples);
    if (pet && (!best || pet->pet < best->pet.pet)) best = PetWith{*pet, other};
  }
  return best;
}

}  // namespace orch::metrics
