#pragma once
// One route of a corridor as the network planner (net_plan.cpp) cuts it into lanes: the
// route extended straight beyond its ends, where its lane starts and ends, where it crosses
// each cut. Internal to map build.
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "core/polyline.hpp"
#include "map/corridor_geometry.hpp"
#include "map/net_plan.hpp"
#include "map/waypoint_file.hpp"

namespace orch::corridor {

// One route of a corridor, extended so that every cut lies on it.
struct Member {
  const WaypointRoute* route = nullptr;
  std::size_t index = 0;    // of the route in the waypoint file
  Polyline line;            // route + straight extensions (lane_extension + slack)
  double first_wp_s = 0;    // arc length of waypoint 0 on `line`
  double lane_start = 0;    // where its lane begins: lane_extension before waypoint 0,
  double lane_end = 0;      // ... and ends: past the last one (less for continuations)
  double lateral = 0;       // m left of the corridor's reference route (naming order)
  std::vector<double> keys; // position along the corridor every kTrackStep of `line`
  std::size_t start_cut = 0;
  std::size_t end_cut = 0;
  std::vector<double> cut_s;  // arc length on `line` of cuts start_cut..end_cut
  const CorridorLine* info = nullptr;  // junction maps: routes and the junctions at its ends
  [[nodiscard]] const std::string& end_node(bool start) const {
    static const std::string none;
    return info ? (start ? info->start_node : info->end_node) : none;
  }
  [[nodiscard]] double cut_at(std::size_t cut) const { return cut_s[cut - start_cut]; }
  [[nodiscard]] bool active_in(std::size_t segment) const { return start_cut <= segment && segment < end_cut; }

  // Position along the corridor of arc length s on `line`, and the reverse (keys[i]
  // belongs to s = i * kTrackStep, the last one to the end of the line).
  [[nodiscard]] double sample_s(std::size_t i) const { return std::min(static_cast<double>(i) * kTrackStep, line.length()); }
  [[nodiscard]] double key_of(double s) const {
    const auto i = std::min(static_cast<std::size_t>(std::max(s, 0.0) / kTrackStep), keys.size() - 2);
    const double f = std::clamp((s - sample_s(i)) / (sample_s(i + 1) - sample_s(i)), 0.0, 1.0);
    return keys[i] + f * (keys[i + 1] - keys[i]);
  }
  [[nodiscard]] double s_of_key(double key) const {
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    if (it == keys.begin()) return 0.0;
    if (it == keys.end()) return line.length();
    const auto i = static_cast<std::size_t>(it - keys.begin()) - 1;
    const double span = keys[i + 1] - keys[i];
    const double f = span > 1e-9 ? (key - keys[i]) / span : 0.0;
    return sample_s(i) + f * (sample_s(i + 1) - sample_s(i));
  }
  [[nodiscard]] double last_wp_s() const { return first_wp_s + route->line.length(); }
};

// The lane's speed between arc lengths s0 and s1 of m.line: the largest target speed v of the
// route's waypoints there (kFallbackLaneSpeed, with a note, when it has none).
double lane_speed(const Member& m, double s0, double s1, std::vector<std::string>& notes);

}  // namespace orch::corridor
