#include "run/trace_writer.hpp"

#include <fmt/format.h>

namespace orch {

TraceWriter::TraceWriter(const std::filesystem::path& path, const LaneMap& lanes, const engine::Engine& engine)
    : file_(path, kHeader), lanes_(lanes), engine_(engine) {
  for (int i = 0; i < static_cast<int>(lanes.lanes().size()); ++i) lane_index_[lanes.lane(i).id] = i;
}

double TraceWriter::lateral_offset(const sim::ActorState& a) const {
  // The centre's offset from the centre of the lane SUMO has the actor on, like x and y.
  // (SUMO's own lateral position is the front's: a car turned 3 degrees to change lanes
  // would read 0.13 m off. Persons have none.)
  if (auto it = lane_index_.find(a.edge + "_" + std::to_string(a.lane)); it != lane_index_.end())
    return lanes_.place_on_lane(it->second, a.position).lateral;
  return a.lat_offset.value_or(0.0);
}

void TraceWriter::record(const engine::Engine& engine, std::optional<sim::ActorId> plugin_driven) {
  const sim::WorldSnapshot& snap = engine.judged();
  for (const auto& a : snap.actors) {
    if (!a.present) continue;
    const char* driver = plugin_driven == a.id    ? "plugin"
                         : engine.scripted(a.id)  ? "script"
                         : model_driven_ == a.id ? model_label_.c_str()
                                                  : "sumo";
    file_.print(FMT_COMPILE("{:.3f},{},{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{},{},{}\n"), snap.time,
               engine.scene(), a.id, a.position.x(), a.position.y(), a.heading, a.speed, a.accel, a.edge, a.lane,
               a.lane_pos, lateral_offset(a), a.signals, a.siren ? 1 : 0, driver);
    ++rows_;
  }
  // Every 200 steps (10 s at 0.05 s) the rows reach the disk even if the process dies.
  file_.end_step(200);
}

}  // namespace orch
