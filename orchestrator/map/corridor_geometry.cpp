#include "map/corridor_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checked_numeric.hpp"

namespace orch::corridor {

Vec2 end_direction(const Polyline& line, bool at_end) {
  const double chord = std::min(kDirectionChord, line.length());
  const Vec2 d = at_end ? line.point_at(line.length()) - line.point_at(line.length() - chord)
                        : line.point_at(chord) - line.point_at(0);
  return d.norm() > 1e-9 ? Vec2(d.normalized()) : line.tangent_at(at_end ? line.length() : 0.0);
}

std::pair<Polyline, double> extend_straight(const Polyline& line, double before, double after) {
  std::vector<Vec2> pts;
  const Vec2 d0 = end_direction(line, false);
  const Vec2 d1 = end_direction(line, true);
  const auto steps = [](double len) { return pieces_covering(len, kExtensionStep, 0, 1 << 30); };
  for (int k = steps(before); k >= 1; --k) pts.push_back(line.point(0) - before * k / steps(before) * d0);
  const auto prefix = pts.size();
  pts.insert(pts.end(), line.points().begin(), line.points().end());
  for (int k = 1; k <= steps(after); ++k) pts.push_back(line.points().back() + after * k / steps(after) * d1);
  Polyline out(std::move(pts));
  const double first_s = out.s_at_index(prefix);
  return {std::move(out), first_s};
}

Polyline::Projection project_along(const Polyline& line, const Vec2& p, const Vec2& direction) {
  const Polyline::Projection fast = line.project(p);
  if (line.tangent_at(fast.s).dot(direction) >= 0.5) return fast;
  Polyline::Projection best = fast;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 a = line.point(i);
    const Vec2 seg = line.point(i + 1) - a;
    const double len = seg.norm();
    if (len < 1e-9 || seg.dot(direction) < 0.5 * len) continue;
    const double f = std::clamp((p - a).dot(seg) / (len * len), 0.0, 1.0);
    const Vec2 foot = a + f * seg;
    const double dist = (p - foot).norm();
    if (dist < best.distance) {
      best.distance = dist;
      best.s = line.s_at_index(i) + f * len;
      best.segment = i;
      best.lateral = (p - foot).dot(left_normal(seg / len));
    }
  }
  return std::isfinite(best.distance) ? best : fast;
}

std::vector<double> track_along(const Polyline& axis, const Polyline& line) {
  const auto n = static_cast<std::size_t>(pieces_covering(line.length(), kTrackStep, 0, 1 << 30)) + 1;
  const auto at = [&](std::size_t i) { return std::min(static_cast<double>(i) * kTrackStep, line.length()); };
  std::vector<double> keys(n);
  const std::size_t mid = n / 2;
  keys[mid] = project_along(axis, line.point_at(at(mid)), line.tangent_at(at(mid))).s;
  for (std::size_t i = mid + 1; i < n; ++i)
    keys[i] = axis.project_near(line.point_at(at(i)), keys[i - 1] + (at(i) - at(i - 1)), kTrackWindow).s;
  for (std::size_t i = mid; i-- > 0;)
    keys[i] = axis.project_near(line.point_at(at(i)), keys[i + 1] - kTrackStep, kTrackWindow).s;
  return keys;
}

double lane_spacing(const Polyline& right, const Polyline& left) {
  double sum = 0;
  int n = 0;
  for (int k = 0; k <= 10; ++k) {
    const double s = left.length() * (0.05 + 0.09 * k);
    const Polyline::Projection p = right.project(left.point_at(s));
    if (p.before_start || p.after_end) continue;
    sum += p.lateral;
    ++n;
  }
  return n > 0 ? sum / n : kDefaultLaneWidth;
}

std::vector<Vec2> centre_line(const PlannedEdge& e) {
  const Polyline& right = e.lanes.front().shape;
  const Polyline& left = e.lanes.back().shape;
  if (e.lanes.size() == 1) return right.points();
  std::vector<Vec2> out;
  for (const Vec2& p : right.points()) out.push_back(0.5 * (p + left.point_at(left.project(p).s)));
  return out;
}

}  // namespace orch::corridor
