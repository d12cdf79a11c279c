#include "core/polyline.hpp"


#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/checked_numeric.hpp"

namespace orch {

bool inside_polygon(const Vec2& p, const std::vector<Vec2>& polygon) {
  if (polygon.size() < 3) return false;
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

double wrap_angle(double a) {
  constexpr double two_pi = 2 * std::numbers::pi;
  a = std::fmod(a, two_pi);
  if (a <= -std::numbers::pi) a += two_pi;
  if (a > std::numbers::pi) a -= two_pi;
  return a;
}

Polyline::Polyline(std::vector<Vec2> points) : points_(std::move(points)) {
  if (points_.size() < 2) throw std::invalid_argument("a polyline needs at least two points");
  cumulative_.resize(points_.size());
  cumulative_[0] = 0;
  for (std::size_t i = 1; i < points_.size(); ++i)
    cumulative_[i] = cumulative_[i - 1] + (points_[i] - points_[i - 1]).norm();
  if (length() <= 0) throw std::invalid_argument("a polyline needs a non-zero length");
  build_grid();
}

namespace {
// Coordinates beyond kGridReach (core/checked_numeric.hpp) are not indexed. A segment whose bounding box covers more cells than this is not indexed cell by cell.
constexpr long long kMaxCellsPerSegment = 65536;
// Beyond this many rings of cells, scanning every segment is cheaper and gives the same result.
constexpr double kMaxRings = 64;
}  // namespace

std::optional<long long> Polyline::cell_of(double v) const {
  if (!(std::abs(v) <= kGridReach)) return std::nullopt;
  return floor_to_integer(v / cell_);
}

void Polyline::build_grid() {
  for (std::size_t seg = 0; seg + 1 < points_.size(); ++seg) {
    const Vec2& a = points_[seg];
    const Vec2& b = points_[seg + 1];
    const auto x0 = cell_of(std::min(a.x(), b.x()));
    const auto x1 = cell_of(std::max(a.x(), b.x()));
    const auto y0 = cell_of(std::min(a.y(), b.y()));
    const auto y1 = cell_of(std::max(a.y(), b.y()));
    if (!x0 || !x1 || !y0 || !y1 || *x1 - *x0 >= kMaxCellsPerSegment || *y1 - *y0 >= kMaxCellsPerSegment ||
        (*x1 - *x0 + 1) * (*y1 - *y0 + 1) > kMaxCellsPerSegment) {
      unindexed_.push_back(seg);
      continue;
    }
    for (long long cx = *x0; cx <= *x1; ++cx)
      for (long long cy = *y0; cy <= *y1; ++cy) grid_[cell_key(cx, cy)].push_back(seg);
  }
}

void Polyline::nearest_of_all(const Vec2& p, Projection& best) const {
  for (std::size_t seg = 0; seg + 1 < points_.size(); ++seg) {
    Projection r = project_on_segment(p, seg);
    if (r.distance < best.distance) best = r;
  }
}

void Polyline::nearest_in(const std::vector<std::size_t>& segments, const Vec2& p, Projection& best) const {
  for (std::size_t seg : segments) {
    Projection r = project_on_segment(p, seg);
    if (r.distance < best.distance) best = r;
  }
}

double Polyline::s_at_fractional_index(double index) const {
  if (!(index > 0)) return 0;  // NaN too
  const double last = static_cast<double>(points_.size() - 1);
  if (index >= last) return length();
  const auto i = static_cast<std::size_t>(std::floor(index));
  const double frac = index - static_cast<double>(i);
  return cumulative_[i] + frac * (cumulative_[i + 1] - cumulative_[i]);
}

std::size_t Polyline::segment_at(double s) const {
  if (s <= 0) return 0;
  if (s >= length()) return points_.size() - 2;
  auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  auto seg = static_cast<std::size_t>(it - cumulative_.begin()) - 1;
  return std::min(seg, points_.size() - 2);
}

Vec2 Polyline::tangent_at(double s) const {
  std::size_t seg = segment_at(s);
  // Zero-length segments have no direction: take the nearest one that has.
  for (std::size_t k = 0; k < points_.size(); ++k) {
    for (long long cand : {static_cast<long long>(seg) + static_cast<long long>(k),
                           static_cast<long long>(seg) - static_cast<long long>(k)}) {
      if (cand < 0 || cand + 1 >= static_cast<long long>(points_.size())) continue;
      const auto c = static_cast<std::size_t>(cand);
      Vec2 d = points_[c + 1] - points_[c];
      if (d.norm() > 1e-9) return d.normalized();
    }
  }
  return {1, 0};
}

double Polyline::heading_at(double s) const {
  const Vec2 t = tangent_at(s);
  return std::atan2(t.y(), t.x());
}

Vec2 Polyline::point_at(double s) const {
  if (s <= 0) return points_.front() + s * tangent_at(0);
  if (s >= length()) return points_.back() + (s - length()) * tangent_at(length());
  const std::size_t seg = segment_at(s);
  const double seg_len = cumulative_[seg + 1] - cumulative_[seg];
  if (seg_len <= 1e-12) return points_[seg];
  const double f = (s - cumulative_[seg]) / seg_len;
  return points_[seg] + f * (points_[seg + 1] - points_[seg]);
}

Vec2 Polyline::offset_point(double s, double lateral) const {
  return point_at(s) + lateral * left_normal(tangent_at(s));
}

Polyline::Projection Polyline::project_on_segment(const Vec2& p, std::size_t seg) const {
  const Vec2& a = points_[seg];
  const Vec2 d = points_[seg + 1] - a;
  const double len2 = d.squaredNorm();
  double f = len2 > 0 ? (p - a).dot(d) / len2 : 0.0;
  f = std::clamp(f, 0.0, 1.0);
  const Vec2 q = a + f * d;
  Projection r;
  r.segment = seg;
  r.s = cumulative_[seg] + f * std::sqrt(len2);
  r.distance = (p - q).norm();
  return r;
}

Polyline::Projection Polyline::finish(Projection best, const Vec2& p) const {
  const Vec2 t = tangent_at(best.s);
  const Vec2 rel = p - point_at(best.s);
  const double along = rel.dot(t);
  best.lateral = rel.dot(left_normal(t));
  // A point past either end projects onto the end; report how far along it lies so callers
  // can tell "beside the end" from "beyond the end".
  if (best.s <= 1e-9 && along < -1e-9) best.before_start = true;
  if (best.s >= length() - 1e-9 && along > 1e-9) best.after_end = true;
  return best;
}

Polyline::Projection Polyline::project(const Vec2& p) const {
  // The grid's rings within 4 cells, else every segment.
  if (auto near = project_within(p, 4 * cell_)) return *near;
  Projection best;
  best.distance = std::numeric_limits<double>::infinity();
  nearest_of_all(p, best);
  return finish(best, p);
}

std::optional<Polyline::Projection> Polyline::project_within(const Vec2& p, double radius) const {
  if (!p.allFinite() || !(radius >= 0)) return std::nullopt;
  Projection best;
  best.distance = std::numeric_limits<double>::infinity();
  nearest_in(unindexed_, p, best);
  const auto cell_x = cell_of(p.x());
  const auto cell_y = cell_of(p.y());
  const double ring_count = std::ceil(radius / cell_);
  if (!cell_x || !cell_y || !(ring_count <= kMaxRings)) {
    nearest_of_all(p, best);
    if (best.distance > radius) return std::nullopt;
    return finish(best, p);
  }
  const long long cx = *cell_x;
  const long long cy = *cell_y;
  const auto rings = static_cast<long long>(ring_count);
  for (long long ring = 0; ring <= rings; ++ring) {
    for (long long dx = -ring; dx <= ring; ++dx)
      for (long long dy = -ring; dy <= ring; ++dy) {
        if (std::max(std::llabs(dx), std::llabs(dy)) != ring) continue;
        // A cell farther than the radius (or the best so far) holds no segment that counts:
        // a segment is listed in every cell its bounding box touches.
        const double reach = std::min(radius, best.distance);
        const double gap_x = std::max({0.0, static_cast<double>(cx + dx) * cell_ - p.x(),
                                       p.x() - static_cast<double>(cx + dx + 1) * cell_});
        const double gap_y = std::max({0.0, static_cast<double>(cy + dy) * cell_ - p.y(),
                                       p.y() - static_cast<double>(cy + dy + 1) * cell_});
        if (gap_x * gap_x + gap_y * gap_y > reach * reach) continue;
        auto it = grid_.find(cell_key(cx + dx, cy + dy));
        if (it == grid_.end()) continue;
        nearest_in(it->second, p, best);
      }
    // A hit within the searched radius cannot be beaten further out.
    if (best.distance <= static_cast<double>(ring) * cell_) break;
  }
  if (best.distance > radius) return std::nullopt;
  return finish(best, p);
}

Polyline::Projection Polyline::project_near(const Vec2& p, double s_hint, double window) const {
  const std::size_t first = segment_at(s_hint - window);
  const std::size_t last = segment_at(s_hint + window);
  // The same answer as measuring every segment of the window in order (the first of equally
  // near ones), without measuring the far ones: every point of the segments after vertex k
  // within arc length D lies within D of it, so those segments are at least
  // |p - points_[k]| - D from p. Segments whose bound exceeds the nearest distance known so
  // far (the hint's segment to begin with) by more than kPruneMargin cannot be the nearest
  // and are skipped; the margin is far above the rounding of these sums and norms (1e-8 m on
  // a 10 km line), so every segment that could tie for the nearest is measured, in order.
  constexpr double kPruneMargin = 1e-4;  // m
  double bound = project_on_segment(p, std::clamp(segment_at(s_hint), first, last)).distance;
  Projection best;
  best.distance = std::numeric_limits<double>::infinity();
  std::size_t seg = first;
  while (seg <= last) {
    const double until = cumulative_[seg] + (p - points_[seg]).norm() - bound - kPruneMargin;
    while (seg <= last && cumulative_[seg + 1] < until) ++seg;  // all of segment seg lies nearer than `until`
    if (seg > last) break;
    Projection r = project_on_segment(p, seg);
    if (r.distance < best.distance) {
      best = r;
      bound = std::min(bound, best.distance);
    }
    ++seg;
  }
  return finish(best, p);
}

Polyline Polyline::slice(double s0, double s1) const {
  std::vector<Vec2> out;
  out.push_back(point_at(s0));
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (cumulative_[i] > s0 + 1e-6 && cumulative_[i] < s1 - 1e-6) out.push_back(points_[i]);
  out.push_back(point_at(s1));
  return Polyline(std::move(out));
}

namespace {
void douglas_peucker(const std::vector<Vec2>& pts, std::size_t first, std::size_t last,
                     double tol, std::vector<bool>& keep) {
  if (last <= first + 1) return;
  const Vec2& a = pts[first];
  const Vec2 d = pts[last] - a;
  const double len = d.norm();
  double worst = -1;
  std::size_t worst_i = first;
  for (std::size_t i = first + 1; i < last; ++i) {
    const Vec2 r = pts[i] - a;
    double dist;
    if (len < 1e-12) {
      dist = r.norm();
    } else {
      const double f = std::clamp(r.dot(d) / (len * len), 0.0, 1.0);
      dist = (r - f * d).norm();
    }
    if (dist > worst) {
      worst = dist;
      worst_i = i;
    }
  }
  if (worst > tol) {
    keep[worst_i] = true;
    douglas_peucker(pts, first, worst_i, tol, keep);
    douglas_peucker(pts, worst_i, last, tol, keep);
  }
}
}  // namespace

Polyline Polyline::simplified(double tolerance) const {
  std::vector<bool> keep(points_.size(), false);
  keep.front() = keep.back() = true;
  douglas_peucker(points_, 0, points_.size() - 1, tolerance, keep);
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (keep[i] && (out.empty() || (points_[i] - out.back()).norm() > 1e-9)) out.push_back(points_[i]);
  return Polyline(std::move(out));
}

}  // namespace orch
