#pragma once
// trace.csv: one row per present actor per step, a contract users script against
// (docs/outputs.md). Rows are written with fixed precision so the same run gives the
// same bytes, and flushed regularly so a crash keeps what was simulated.
#include <filesystem>
#include <optional>
#include <string>
#include <unordered_map>

#include "core/output_file.hpp"
#include "scenario_executor_engine/engine.hpp"
#include "map/lane_map.hpp"
#include "run/run_observer.hpp"
#include "run/run_result.hpp"

namespace orch {

class TraceWriter : public RunObserver {
 public:
  [[nodiscard]] const char* name() const override { return "trace"; }
  static constexpr const char* kHeader =
      "time,scene_id,actor_id,x,y,heading,speed,accel,edge,lane,lane_pos,lat_offset,signals,siren,driver";

  // `engine`: the run's scene graph (the scene and who drives each actor).
  TraceWriter(const std::filesystem::path& path, const LaneMap& lanes, const engine::Engine& engine);

  // The actor a built-in ego model drives (driver `label`, e.g. "r157") instead of SUMO's.
  void set_model_driven(sim::ActorId id, std::string label) {
    model_driven_ = id;
    model_label_ = std::move(label);
  }
  // `plugin_driven`: the actor an external ego plug-in drove in this step (driver "plugin").
  void record(const engine::Engine& engine, std::optional<sim::ActorId> plugin_driven = std::nullopt);
  void flush() { file_.flush(); }
  [[nodiscard]] long long rows() const { return rows_; }

  void step(const StepView& view) override { record(engine_, view.plugin_driven); }
  void finish(RunResult& result) noexcept override {
    flush();
    result.trace_rows = rows_;
  }

 private:
  [[nodiscard]] double lateral_offset(const sim::ActorState& a) const;

  OutputFile file_;
  const LaneMap& lanes_;
  const engine::Engine& engine_;
  std::unordered_map<std::string, int> lane_index_;  // SUMO lane id -> LaneMap index
  std::optional<sim::ActorId> model_driven_;
  std::string model_label_ = "sumo";
  long long rows_ = 0;
};

}  // namespace orch
