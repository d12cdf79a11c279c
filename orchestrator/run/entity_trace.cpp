#include "run/entity_trace.hpp"

#include "run/run_result.hpp"
#include "run/trace_writer.hpp"

namespace orch {

EntityTrace::EntityTrace(const std::filesystem::path& path, const OpenScenarioActors& actors,
                         std::function<const char*()> ego_driver)
    : file_(path, TraceWriter::kHeader), actors_(actors), ego_driver_(std::move(ego_driver)) {}

void EntityTrace::step(const StepView& view) {
  const double time = view.run.judged().time;
  const std::string& ego = actors_.ego();
  for (const auto& a : view.snapshot.actors) {
    if (!a.present) continue;
    const Vec2 ref = actors_.reference_point(a);
    const std::string& name = actors_.name_of(a.id);
    file_.print("{:.3f},,{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{},0,{}\n", time, name,
               ref.x(), ref.y(), a.heading, a.speed, a.accel, a.edge, a.lane, a.lane_pos, a.lat_offset.value_or(0.0),
               a.signals, name == ego ? ego_driver_() : (actors_.is_sumo_driven(name) ? "sumo" : "script"));
    ++rows_;
  }
  file_.end_step(200);
}

void EntityTrace::finish(RunResult& result) noexcept {
  file_.flush();
  result.trace_rows = rows_;
}

}  // namespace orch
