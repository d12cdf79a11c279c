#pragma once
// Synthetic RoadEditor waypoint files for the map tests: roads made of a straight part and
// an arc, with routes at chosen lateral offsets, written into a temporary folder. Header
// only, shared by the unit and integration tests ("unit/synthetic_roads.hpp").
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/polyline.hpp"

namespace orch::test {

// A folder under the system temp dir, removed with everything in it at the end of a test.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("orch_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A road centre line: `straight` metres along `heading` from `start`, then an arc of
// `radius` metres (+ = turning left, - = right, 0 = none) for `arc_length` metres, then a
// second arc (`radius2`, `arc_length2`; an S-curve when the signs differ), then straight on.
struct RoadShape {
  Vec2 start{0, 0};
  double heading = 0;  // rad
  double straight = 500;
  double radius = 0;
  double arc_length = 0;
  double radius2 = 0;
  double arc_length2 = 0;

  [[nodiscard]] double length() const { return straight + arc_length + arc_length2; }
  // Point at arc length s of the centre line (s may run past the end), moved `lateral`
  // metres to the left.
  [[nodiscard]] Vec2 at(double s, double lateral) const {
    Vec2 p = start;
    double h = heading;
    const std::pair<double, double> pieces[] = {{straight, 0.0},
                                                {radius == 0 ? 0.0 : arc_length, radius},
                                                {radius2 == 0 ? 0.0 : arc_length2, radius2},
                                                {1e12, 0.0}};
    double rest = s;
    for (const auto& [len, r] : pieces) {
      const double d = std::min(rest, len);
      if (r == 0) {
        p += d * Vec2(std::cos(h), std::sin(h));
      } else {
        // Arc of signed radius r: the centre lies r to the left; heading turns by d / r.
        const Vec2 centre = p + r * left_normal(Vec2(std::cos(h), std::sin(h)));
        h += d / r;
        p = centre - r * left_normal(Vec2(std::cos(h), std::sin(h)));
      }
      rest -= d;
      if (rest <= 0) break;
    }
    return p + lateral * left_normal(Vec2(std::cos(h), std::sin(h)));
  }
};

struct SyntheticRoute {
  std::string id;
  std::vector<Vec2> points;  // map frame
  double speed_kmh = 60;
};

// Points every `step` metres between arc lengths s0 and s1 of the road, `lateral` m left of
// its centre line; reverse = driven the other way.
inline std::vector<Vec2> road_points(const RoadShape& road, double lateral, double s0, double s1, double step = 1.0,
                                     bool reverse = false) {
  std::vector<Vec2> pts;
  const int n = static_cast<int>(std::floor((s1 - s0) / step + 1e-9));
  for (int i = 0; i <= n; ++i) pts.push_back(road.at(s0 + i * step, lateral));
  if (reverse) std::reverse(pts.begin(), pts.end());
  return pts;
}

// The JSON RoadEditor writes: file x = map x, file z = -map y, file y = height, v in km/h.
inline std::string waypoint_json(const std::string& map_id, const std::vector<SyntheticRoute>& routes) {
  nlohmann::ordered_json j;
  j["id"] = "WayPoint_" + map_id;
  j["mapId"] = map_id;
  j["waypoints"] = nlohmann::ordered_json::array();
  for (const auto& r : routes) {
    nlohmann::ordered_json route;
    route["id"] = r.id;
    route["points"] = nlohmann::ordered_json::array();
    for (const Vec2& p : r.points)
      route["points"].push_back({{"x", p.x()}, {"y", 0.0}, {"z", -p.y()}, {"v", r.speed_kmh}});
    j["waypoints"].push_back(route);
  }
  j["properties"] = nlohmann::ordered_json::array();
  return j.dump(1);
}

inline std::filesystem::path write_waypoint_file(const std::filesystem::path& dir, const std::string& map_id,
                                                 const std::vector<SyntheticRoute>& routes) {
  const auto path = dir / (map_id + ".waypoint.json");
  std::ofstream(path) << waypoint_json(map_id, routes);
  return path;
}

}  // namespace orch::test
