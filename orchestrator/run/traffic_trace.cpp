#include "run/traffic_trace.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace orch {

namespace {
std::FILE* open_csv(const std::filesystem::path& path, const char* header) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw OrchError("cannot write " + path.string());
  fmt::print(f, "{}\n", header);
  return f;
}
}  // namespace

TrafficTrace::TrafficTrace(const std::filesystem::path& dir, bool background_rows) {
  counts_ = open_csv(dir / "counts.csv", kCountsHeader);
  if (background_rows) background_ = open_csv(dir / "background.csv", kBackgroundHeader);
}

TrafficTrace::~TrafficTrace() {
  if (counts_) std::fclose(counts_);
  if (background_) std::fclose(background_);
}

void TrafficTrace::record(const engine::WorldSnapshot& snap) {
  fmt::print(counts_, "{:.3f},{},{},{}\n", snap.time, snap.other_vehicles, snap.nearby.size(), snap.long_waiting);
  if (background_) {
    for (const auto& v : snap.nearby) {
      fmt::print(background_, "{:.3f},{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{:.3f}\n", snap.time, v.sumo_id,
                 v.position.x(), v.position.y(), v.heading, v.speed, v.length, v.width);
      ++background_rows_;
    }
  }
  // As trace.csv: every 200 steps the rows reach the disk even if the process dies.
  if (++steps_since_flush_ >= 200) flush();
}

void TrafficTrace::flush() {
  std::fflush(counts_);
  if (background_) std::fflush(background_);
  steps_since_flush_ = 0;
}

}  // namespace orch
