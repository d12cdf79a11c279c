#include "run/trace_writer.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace orch {

TraceWriter::TraceWriter(const std::filesystem::path& path, const LaneMap& lanes) : lanes_(lanes) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw OrchError("cannot write " + path.string());
  fmt::print(file_, "{}\n", kHeader);
}

TraceWriter::~TraceWriter() {
  if (file_) std::fclose(file_);
}

double TraceWriter::lateral_offset(const engine::ActorState& a) const {
  if (a.lat_offset) return *a.lat_offset;
  // Persons have no lateral lane position in SUMO: measure it on the lane's shape.
  for (int i = 0; i < static_cast<int>(lanes_.lanes().size()); ++i) {
    const LaneInfo& lane = lanes_.lane(i);
    if (lane.edge == a.edge && lane.index == a.lane) return lanes_.place_on_lane(i, a.position).lateral;
  }
  return 0.0;
}

void TraceWriter::record(const engine::Engine& engine) {
  const engine::WorldSnapshot& snap = engine.judged();
  for (const auto& a : snap.actors) {
    if (!a.present) continue;
    const char* driver = engine.scripted(a.id) ? "script" : "sumo";
    fmt::print(file_, "{:.3f},{},{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{},{},{}\n", snap.time,
               engine.scene(), a.id, a.position.x(), a.position.y(), a.heading, a.speed, a.accel, a.edge, a.lane,
               a.lane_pos, lateral_offset(a), a.signals, engine.siren(a.id) ? 1 : 0, driver);
    ++rows_;
  }
  // Every 200 steps (10 s at 0.05 s) the rows reach the disk even if the process dies.
  if (++steps_since_flush_ >= 200) flush();
}

void TraceWriter::flush() {
  std::fflush(file_);
  steps_since_flush_ = 0;
}

}  // namespace orch
