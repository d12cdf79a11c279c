#include "run/entity_trace.hpp"

#include "run/run_result.hpp"
#include "run/trace_writer.hpp"

namespace orch {

EntityTrace::EntityTrace(const std::filesystem::path& path, const OpenScenarioActors& actors,
                         const opendrive::RoadNetwork& roads, std::function<const char*()> ego_driver)
    : file_(path, std::string(TraceWriter::kHeader) + kExtraColumns),
      actors_(actors),
      roads_(roads),
      ego_driver_(std::move(ego_driver)) {}

namespace {

// The road surface under a point (0, 0, 0 off every road).
opendrive::SurfacePose surface_under(const opendrive::RoadNetwork& roads, const Vec2& at, double heading) {
  const auto c = roads.to_road(at.x(), at.y());
  if (!c) return {};
  const opendrive::Road& road = roads.road(c->road_id);
  if (!road.lane_at(c->s, c->t)) return {};
  return opendrive::surface_pose(road, c->s, c->t, heading);
}

}  // namespace

void EntityTrace::step(const StepView& view) {
  const double time = view.run.judged().time;
  const std::string& ego = actors_.ego();
  for (const auto& a : view.snapshot.actors) {
    if (!a.present) continue;
    const Vec2 ref = actors_.reference_point(a);
    const std::string& name = actors_.name_of(a.id);
    const opendrive::SurfacePose surface = surface_under(roads_, ref, a.heading);
    file_.print(FMT_COMPILE("{:.3f},,{},{:.3f},{:.3f},{:.4f},{:.3f},{:.3f},{},{},{:.3f},{:.3f},{},0,{},{:.3f},{:.4f},{:.4f}\n"), time,
               name, ref.x(), ref.y(), a.heading, a.speed, a.accel, a.edge, a.lane, a.lane_pos,
               a.lat_offset.value_or(0.0), a.signals,
               name == ego ? ego_driver_() : (actors_.is_sumo_driven(name) ? "sumo" : "script"), surface.z + actors_.height_of(name) + 0.0,
               surface.pitch + 0.0, surface.roll + 0.0);
    ++rows_;
  }
  file_.end_step(200);
}

void EntityTrace::finish(RunResult& result) noexcept {
  file_.flush();
  result.trace_rows = rows_;
}

}  // namespace orch
