#include "run/traffic_trace.hpp"

#include <algorithm>

namespace orch {

TrafficTrace::TrafficTrace(const std::filesystem::path& dir, bool background_rows)
    : counts_(dir / "counts.csv", kCountsHeader) {
  if (background_rows) background_.emplace(dir / "background.csv", kBackgroundHeader);
}

void TrafficTrace::record(const sim::WorldSnapshot& snap) {
  counts_.print(FMT_COMPILE("{:.3f},{},{},{}\n"), snap.time, snap.other_vehicles, snap.nearby.size(), snap.long_waiting);
  if (background_) {
    // An OpenSCENARIO run's TrafficAction vehicles are near the entities too: they have their
    // own file (traffic_actions.csv); both lists are in id order.
    const auto by_id = [](const sim::NearbyVehicle& a, const sim::NearbyVehicle& b) { return a.sumo_id < b.sumo_id; };
    for (const auto& v : snap.nearby) {
      if (std::binary_search(snap.traffic.begin(), snap.traffic.end(), v, by_id)) continue;
      background_->print(FMT_COMPILE("{:.3f},{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{:.3f}\n"), snap.time, v.sumo_id,
                 v.position.x(), v.position.y(), v.heading, v.speed, v.length, v.width);
      ++background_rows_;
    }
  }
  // As trace.csv: every 200 steps the rows reach the disk even if the process dies.
  if (++steps_since_flush_ >= 200) flush();
}

void TrafficTrace::flush() {
  counts_.flush();
  if (background_) background_->flush();
  steps_since_flush_ = 0;
}

}  // namespace orch
