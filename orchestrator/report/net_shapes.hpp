#pragma once
// The lane shapes of a SUMO net, for drawing the map under a run's trajectories. The
// trace's x, y are SUMO's own coordinates, so the shapes are used as they are.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace orch::report {

struct LaneShape {
  std::string id;
  double width = 3.2;     // m (SUMO's default when the net gives none)
  bool internal = false;  // a junction's inner lane (edge function="internal")
  std::vector<double> xy;  // x0, y0, x1, y1, ...
};

struct Bounds {
  double min_x, min_y, max_x, max_y;
  [[nodiscard]] bool overlaps(const Bounds& o) const {
    return min_x <= o.max_x && o.min_x <= max_x && min_y <= o.max_y && o.min_y <= max_y;
  }
};

// Every normal and internal lane of `net_file` whose shape's bounding box overlaps `within`
// (all lanes without it); walking areas and crossings are left out. Throws OrchError naming
// the file when it cannot be read or parsed, or a shape is malformed.
std::vector<LaneShape> read_lane_shapes(const std::filesystem::path& net_file, std::optional<Bounds> within);

}  // namespace orch::report
