#include "opendrive/road_network.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/checked_numeric.hpp"
#include "core/errors.hpp"

namespace orch::opendrive {

const CubicRecord* record_at(const std::vector<CubicRecord>& records, double s) {
  // Binary search (records sorted by s, as the reader sorts them): the first record
  // starting past s, and the one before it.
  const auto past = std::partition_point(records.begin(), records.end(),
                                         [&](const CubicRecord& r) { return r.s <= s + 1e-9; });
  return past == records.begin() ? nullptr : &*(past - 1);
}

double CubicRecord::largest_magnitude(double length) const {
  for (const double k : {a, b, c, d, length})
    if (!std::isfinite(k)) return std::numeric_limits<double>::quiet_NaN();
  double largest = std::max(std::abs(value(0.0)), std::abs(value(length)));
  // slope(x) = b + 2c x + 3d x^2 = 0
  const auto consider = [&](double x) {
    if (x > 0.0 && x < length) largest = std::max(largest, std::abs(value(x)));
  };
  if (d == 0.0) {
    if (c != 0.0) consider(-b / (2.0 * c));
  } else {
    const double discriminant = 4.0 * c * c - 12.0 * d * b;
    if (discriminant >= 0.0) {
      const double root = std::sqrt(discriminant);
      consider((-2.0 * c + root) / (6.0 * d));
      consider((-2.0 * c - root) / (6.0 * d));
    }
  }
  return largest;
}

double Lane::width(double ds_in_section) const {
  const CubicRecord* r = record_at(widths, ds_in_section);
  if (r == nullptr) return widths.empty() ? 0.0 : widths.front().value(0.0);
  return r->value(ds_in_section - r->s);
}

const Lane* LaneSection::lane(int id) const {
  const auto& side = id > 0 ? left : right;
  for (const Lane& l : side)
    if (l.id == id) return &l;
  return nullptr;
}

const LaneSection& Road::section_at(double s) const {
  if (sections.empty()) throw MapError(fmt::format("OpenDRIVE road {} has no lane section", id));
  auto it = std::upper_bound(sections.begin(), sections.end(), s + 1e-9,
                             [](double value, const LaneSection& section) { return value < section.s; });
  if (it != sections.begin()) --it;
  return *it;
}

double Road::lane_offset(double s) const {
  const CubicRecord* r = record_at(lane_offsets, s);
  return r == nullptr ? 0.0 : r->value(s - r->s);
}

std::pair<double, double> Road::lane_borders(int lane_id, double s) const {
  const LaneSection& section = section_at(s);
  const double ds = s - section.s;
  const double sign = lane_id > 0 ? 1.0 : -1.0;
  double inner = lane_offset(s);
  if (lane_id == 0) return {inner, inner};
  // Lanes are stacked outward from the centre lane: 1, 2, ... to the left, -1, -2, ... right.
  const int step = lane_id > 0 ? 1 : -1;
  for (int current = step; std::abs(current) <= std::abs(lane_id); current += step) {
    const Lane* lane = section.lane(current);
    if (lane == nullptr)
      throw MapError(fmt::format("OpenDRIVE road {} has no lane {} at s={:.3f}", id, lane_id, s));
    const double outer = inner + sign * lane->width(ds);
    if (current == lane_id) return {inner, outer};
    inner = outer;
  }
  throw MapError(fmt::format("OpenDRIVE road {} has no lane {} at s={:.3f}", id, lane_id, s));
}

double Road::lane_center_t(int lane_id, double s) const {
  const auto [inner, outer] = lane_borders(lane_id, s);
  return 0.5 * (inner + outer);
}

Road::LaneSpan Road::lane_span_at(double s, double t) const {
  const LaneSection& section = section_at(s);
  const double ds = s - section.s;
  const double centre = lane_offset(s);
  const bool left = t >= centre;
  const auto& side = left ? section.left : section.right;
  double inner = centre;
  for (const Lane& lane : side) {
    const double width = lane.width(ds);
    const double outer = inner + (left ? width : -width);
    if (left ? (t >= inner && t <= outer) : (t <= inner && t >= outer)) return {&lane, ds, inner, width};
    inner = outer;
  }
  return {};
}

std::optional<int> Road::lane_at(double s, double t) const {
  const LaneSpan span = lane_span_at(s, t);
  if (span.lane == nullptr) return std::nullopt;
  return span.lane->id;
}

double Road::lane_height(double s, double t) const {
  const LaneSpan span = lane_span_at(s, t);
  if (span.lane == nullptr) return 0.0;
  const auto& heights = span.lane->heights;
  const auto past = std::partition_point(heights.begin(), heights.end(),
                                         [&](const LaneHeight& h) { return h.s_offset <= span.ds + 1e-9; });
  if (past == heights.begin()) return 0.0;
  const LaneHeight& h = *(past - 1);
  const double across = span.width > 0.0 ? std::abs(t - span.inner) / span.width : 0.0;
  return h.inner + (h.outer - h.inner) * across;
}

Pose2 Road::world(double s, double t) const {
  const Pose2 ref = plan_view.pose(s);
  const double side = superelevations.empty() ? t : t * std::cos(roll(s));
  return {ref.x - side * std::sin(ref.heading), ref.y + side * std::cos(ref.heading), ref.heading};
}

double Road::elevation(double s) const {
  const CubicRecord* r = record_at(elevations, s);
  return r == nullptr ? 0.0 : r->value(s - r->s);
}

double Road::elevation_slope(double s) const {
  const CubicRecord* r = record_at(elevations, s);
  return r == nullptr ? 0.0 : r->slope(s - r->s);
}

double Road::roll(double s) const {
  const CubicRecord* r = record_at(superelevations, s);
  return r == nullptr ? 0.0 : r->value(s - r->s);
}

SurfacePose surface_pose(const Road& road, double s, double t, double heading) {
  // The surface's gradient in the road's frame (forward along s, left across it), turned
  // into the body's frame.
  const double forward = road.elevation_slope(s);
  const double road_roll = road.roll(s);
  const double left = std::tan(road_roll);
  const double turn = heading - road.plan_view.pose(s).heading;
  const double along_body = forward * std::cos(turn) + left * std::sin(turn);
  const double across_body = -forward * std::sin(turn) + left * std::cos(turn);
  return {road.height(s, t), -std::atan(along_body), std::atan(across_body)};
}

RoadNetwork::RoadNetwork(std::vector<Road> roads, std::vector<Junction> junctions)
    : roads_(std::move(roads)), junctions_(std::move(junctions)) {
  for (std::size_t i = 0; i < roads_.size(); ++i) index_.emplace(roads_[i].id, i);
  grid_ = RoadGrid(roads_);
}

const Junction* RoadNetwork::junction(const std::string& junction_id) const {
  for (const Junction& j : junctions_)
    if (j.id == junction_id) return &j;
  return nullptr;
}

const Road* RoadNetwork::find(const std::string& road_id) const {
  const auto it = index_.find(road_id);
  return it == index_.end() ? nullptr : &roads_[it->second];
}

const Road& RoadNetwork::road(const std::string& road_id) const {
  const Road* r = find(road_id);
  if (r == nullptr) throw MapError(fmt::format("the OpenDRIVE network has no road {}", road_id));
  return *r;
}

Pose2 RoadNetwork::lane_pose(const std::string& road_id, int lane_id, double s, double offset) const {
  const Road& r = road(road_id);
  return r.world(s, r.lane_center_t(lane_id, s) + offset);
}

RoadCoordinate project(const Road& road, double x, double y) {
  // Coarse: the nearest of samples every ~1 m (from the plan view's tree of them); fine:
  // Newton on (q - p(s)) . T(s) = 0.
  const double length = road.plan_view.length();
  const PointTree& samples = road.plan_view.samples();
  double s = samples.size() < 2 ? 0.0 : road.plan_view.sample_s(samples.nearest(x, y));
  for (int i = 0; i < 30; ++i) {
    const Pose2 p = road.plan_view.pose(s);
    const double along = (x - p.x) * std::cos(p.heading) + (y - p.y) * std::sin(p.heading);
    const double across = -(x - p.x) * std::sin(p.heading) + (y - p.y) * std::cos(p.heading);
    const double denom = 1.0 - road.plan_view.curvature(s) * across;
    const double step = std::abs(denom) > 1e-6 ? along / denom : along;
    const double next = std::clamp(s + step, 0.0, length);
    if (std::abs(next - s) < 1e-10) break;
    s = next;
  }
  const Pose2 p = road.plan_view.pose(s);
  const double side = -(x - p.x) * std::sin(p.heading) + (y - p.y) * std::cos(p.heading);
  // Back from the projected offset to t along the (rolled) surface; the reader keeps the
  // roll within +-75 degrees.
  const double t = road.superelevations.empty() ? side : side / std::cos(road.roll(s));
  return {road.id, s, t, p.heading};
}

namespace {

// to_road's choice: a road holding the point on a lane beats one that does not; then the
// nearer one; on a tie the earlier road.
struct NearestRoad {
  std::optional<RoadCoordinate> best;
  bool best_on_lane = false;
  double best_distance = std::numeric_limits<double>::infinity();

  void consider(const Road& r, double x, double y) {
    const RoadCoordinate c = project(r, x, y);
    const Pose2 ref = r.world(c.s, c.t);
    const double distance = std::hypot(ref.x - x, ref.y - y) + std::abs(c.t) * 1e-9;
    const bool on_lane = r.lane_at(c.s, c.t).has_value() && distance < 1e-3;
    if ((on_lane && !best_on_lane) || (on_lane == best_on_lane && distance < best_distance)) {
      best = c;
      best_on_lane = on_lane;
      best_distance = distance;
    }
  }
};

}  // namespace

std::optional<RoadCoordinate> RoadNetwork::to_road(double x, double y) const {
  // Every road that can hold (x, y) on a lane is a candidate, in road order, so when one
  // does, the choice over the candidates is the choice over all roads.
  NearestRoad near;
  for (const std::uint32_t i : grid_.candidates(x, y)) near.consider(roads_[i], x, y);
  if (near.best_on_lane) return near.best;
  NearestRoad all;  // off every lane: the nearest of all roads
  for (const Road& r : roads_) all.consider(r, x, y);
  return all.best;
}

}  // namespace orch::opendrive
