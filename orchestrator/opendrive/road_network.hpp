#pragma once
// An OpenDRIVE road network as plain values: roads with their reference line, lane offset,
// lane sections and lanes, and the frame conversions (road, lane, s, t) <-> (x, y, heading).
#include <map>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "opendrive/plan_view.hpp"
#include "opendrive/road_grid.hpp"
#include "opendrive/road_links.hpp"

namespace orch::opendrive {

// a + b ds + c ds^2 + d ds^3 with ds measured from `s` (laneOffset, width, speed records).
struct CubicRecord {
  double s = 0.0;  // start, in the unit the owner defines (road s or offset in the section)
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
  [[nodiscard]] double value(double ds) const { return a + ds * (b + ds * (c + ds * d)); }
  [[nodiscard]] double slope(double ds) const { return b + ds * (2 * c + ds * 3 * d); }
  // The largest |value| over ds in [0, length]: at an end or where the slope is zero.
  // NaN when a coefficient is not finite.
  [[nodiscard]] double largest_magnitude(double length) const;
};

// The record in effect at `s` (the last starting at or before it), or nullptr.
const CubicRecord* record_at(const std::vector<CubicRecord>& records, double s);

struct SpeedRecord {
  double s_offset = 0.0;  // from the section start
  double max_mps = 0.0;
};

// <height sOffset inner outer>: the lane's surface raised above the road's (a curb), at its
// inner and outer border (OpenDRIVE 1.6, 9.5.7 Lane height).
struct LaneHeight {
  double s_offset = 0.0;  // from the section start
  double inner = 0.0, outer = 0.0;
};

struct Lane {
  int id = 0;
  std::string type;                 // "driving", "stop", "border", "shoulder", "sidewalk", ...
  std::vector<CubicRecord> widths;  // s = sOffset from the section start
  std::vector<SpeedRecord> speeds;
  std::vector<LaneHeight> heights;  // sorted by s_offset
  std::optional<int> predecessor, successor;  // lane <link>: the lane before / after this section
  [[nodiscard]] double width(double ds_in_section) const;
};

struct LaneSection {
  double s = 0.0;
  std::vector<Lane> left;   // ids 1, 2, ... (sorted outward)
  std::vector<Lane> right;  // ids -1, -2, ... (sorted outward)
  [[nodiscard]] const Lane* lane(int id) const;
};

struct Road {
  std::string id;
  std::string name;
  double length = 0.0;
  std::string junction = "-1";
  bool left_hand_traffic = false;
  std::optional<double> type_speed_mps;  // road <type><speed max>, when given
  std::string type;                      // road <type type>: "motorway", "town", ... ("" when none)
  PlanView plan_view;
  std::vector<CubicRecord> lane_offsets;  // s = road s
  std::vector<CubicRecord> elevations;      // <elevationProfile>: height of the reference line, s = road s
  std::vector<CubicRecord> superelevations; // <lateralProfile>: roll of the cross section (rad, + falls to the right)
  std::vector<LaneSection> sections;      // sorted by s
  RoadLink predecessor, successor;        // road <link>: what touches s = 0 / s = length

  [[nodiscard]] const LaneSection& section_at(double s) const;
  [[nodiscard]] double lane_offset(double s) const;
  // Lateral position t of a lane's inner and outer border at s (t grows to the left).
  // Throws MapError when the lane does not exist at s.
  [[nodiscard]] std::pair<double, double> lane_borders(int lane_id, double s) const;
  [[nodiscard]] double lane_center_t(int lane_id, double s) const;
  // The lane holding lateral position t at s (0 = on the reference line with no lane).
  [[nodiscard]] std::optional<int> lane_at(double s, double t) const;
  // Point at (s, t) in the inertial frame; heading is the reference line's heading at s.
  // t is measured along the road's surface: with superelevation the cross section is rolled
  // about the reference line, so the point lies t cos(roll) to the side (OpenDRIVE 1.6,
  // 8.4.1: superelevation does not change a lane's width, only its projected width).
  [[nodiscard]] Pose2 world(double s, double t) const;

  // The road's surface at (s, t): the height of the point, the reference line's slope and
  // the cross section's roll (0 where the file gives no profile).
  [[nodiscard]] double elevation(double s) const;
  [[nodiscard]] double elevation_slope(double s) const;
  [[nodiscard]] double roll(double s) const;
  [[nodiscard]] double height(double s, double t) const {
    return elevation(s) + t * std::sin(roll(s)) + lane_height(s, t);
  }
  // The lane height at (s, t): the <height> record in effect in the lane holding t, from its
  // inner value at the inner border to its outer value at the outer border (0 off the lanes).
  [[nodiscard]] double lane_height(double s, double t) const;

 private:
  // The lane at (s, t) (nullptr: none), with s within its section, its inner border's t and
  // its width there.
  struct LaneSpan {
    const Lane* lane = nullptr;
    double ds = 0, inner = 0, width = 0;
  };
  [[nodiscard]] LaneSpan lane_span_at(double s, double t) const;
};

// The attitude of a body standing on the surface at (s, t) facing `heading` (inertial):
// z of the surface, pitch (rad, + nose down, ISO 8855 as OpenSCENARIO) and roll (rad, + right side down).
struct SurfacePose {
  double z = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
};
SurfacePose surface_pose(const Road& road, double s, double t, double heading);

// A position in the road frame of one road.
struct RoadCoordinate {
  std::string road_id;
  double s = 0.0;
  double t = 0.0;
  double road_heading = 0.0;  // heading of the reference line at s
};

// An OpenDRIVE <controller>: a signal group, the signals (<control signalId>) that share one
// signal cycle. OpenSCENARIO's TrafficSignalController names one by its id (the standard,
// 6.11.2) and its phases' TrafficSignalGroupState sets all of its signals.
struct SignalController {
  std::string id;
  std::string name;
  std::vector<std::string> signals;
};

// Where the network lies on the earth: the header's <geoReference> (a PROJ string; empty: a
// local frame) and its <offset> (OpenDRIVE 1.6+, 8.5: world = R(hdg) * local + (x, y, z), the
// world being the PROJ string's projected frame).
struct GeoReference {
  std::string proj;
  double x = 0.0, y = 0.0, z = 0.0, hdg = 0.0;
};

class RoadNetwork {
 public:
  RoadNetwork() = default;
  explicit RoadNetwork(std::vector<Road> roads, std::vector<Junction> junctions = {});
  [[nodiscard]] const std::vector<Road>& roads() const { return roads_; }
  [[nodiscard]] const Road* find(const std::string& road_id) const;
  // Throws MapError naming the road when it is missing.
  [[nodiscard]] const Road& road(const std::string& road_id) const;
  [[nodiscard]] const std::vector<Junction>& junctions() const { return junctions_; }
  [[nodiscard]] const Junction* junction(const std::string& junction_id) const;
  [[nodiscard]] const std::vector<SignalController>& signal_controllers() const { return signal_controllers_; }
  void set_signal_controllers(std::vector<SignalController> controllers) { signal_controllers_ = std::move(controllers); }
  [[nodiscard]] const GeoReference& geo_reference() const { return geo_reference_; }
  void set_geo_reference(GeoReference reference) { geo_reference_ = std::move(reference); }

  // Inertial pose of the centre of `lane_id` at s, moved `offset` metres to the left of it.
  [[nodiscard]] Pose2 lane_pose(const std::string& road_id, int lane_id, double s, double offset) const;
  // The road point nearest to (x, y): the road whose reference line is closest and on whose
  // lanes the point lies (any road when none holds it), s and t on it. Only the roads the
  // grid lists near (x, y) are projected onto, every road only when none holds the point.
  [[nodiscard]] std::optional<RoadCoordinate> to_road(double x, double y) const;

 private:
  std::vector<Road> roads_;
  std::map<std::string, std::size_t> index_;
  RoadGrid grid_;
  std::vector<Junction> junctions_;
  std::vector<SignalController> signal_controllers_;
  GeoReference geo_reference_;
};

// Projection of (x, y) onto one road's reference line: nearest s in [0, length] and signed t
// (from the nearest of the reference line's samples, then Newton; O(log length)).
RoadCoordinate project(const Road& road, double x, double y);

}  // namespace orch::opendrive
