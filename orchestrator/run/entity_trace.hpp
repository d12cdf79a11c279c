#pragma once
// trace.csv of an OpenSCENARIO run, with the columns of ScenarioExecutor runs
// (TraceWriter::kHeader) and three more, z, pitch, roll: x, y are the entity's reference point
// in the OpenDRIVE frame (SUMO's coordinates are the same, the conversion keeps them), as SUMO
// has placed it; z, pitch and roll are the road surface's under it, from the OpenDRIVE
// elevation profile and superelevation (0 off every road); actor_id is the entity's name; the
// row's time is the storyboard's (the step's judged time).
#include <filesystem>
#include <functional>
#include <string>

#include "core/output_file.hpp"
#include "opendrive/road_network.hpp"
#include "run/openscenario_world.hpp"
#include "run/run_observer.hpp"

namespace orch {

class EntityTrace : public RunObserver {
 public:
  // `ego_driver`: the ego's `driver` column this step (sumo, script, plugin or r157;
  // openscenario_ego.hpp).
  EntityTrace(const std::filesystem::path& path, const OpenScenarioActors& actors, const opendrive::RoadNetwork& roads,
              std::function<const char*()> ego_driver);
  static constexpr const char* kExtraColumns = ",z,pitch,roll";

  [[nodiscard]] const char* name() const override { return "trace"; }
  void step(const StepView& view) override;
  void finish(RunResult& result) noexcept override;

 private:
  OutputFile file_;
  const OpenScenarioActors& actors_;
  const opendrive::RoadNetwork& roads_;
  std::function<const char*()> ego_driver_;
  long long rows_ = 0;
};

}  // namespace orch
