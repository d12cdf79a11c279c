#pragma once
// traffic_actions.csv of an OpenSCENARIO run: the vehicles of the storyboard's TrafficActions
// (swarm, source; run/openscenario_traffic.hpp), one row per vehicle in SUMO per step, with
// background.csv's columns (TrafficTrace::kBackgroundHeader) and `traffic`, the TrafficAction it
// belongs to: its place (1, 2, ...) in result.json's storyboard_traffic.actions (the order started).
// trace.csv keeps the storyboard's entities only, background.csv the --traffic vehicles; the
// report draws this file's vehicles in the replay. Written once a TrafficAction has started
// (a run without one has no file); the row's time is the storyboard's, as in trace.csv.
#include <filesystem>
#include <functional>
#include <optional>

#include "core/output_file.hpp"
#include "openscenario/traffic_book.hpp"
#include "run/run_observer.hpp"

namespace orch {

class TrafficActionsTrace : public RunObserver {
 public:
  static constexpr const char* kExtraColumns = ",traffic";
  static constexpr const char* kFile = "traffic_actions.csv";

  // `book`: the storyboard's traffic now (nullptr before the storyboard runs).
  TrafficActionsTrace(std::filesystem::path dir, std::function<const openscenario::TrafficBook*()> book);

  [[nodiscard]] const char* name() const override { return "traffic_actions_trace"; }
  void step(const StepView& view) override;
  void finish(RunResult& result) noexcept override;

 private:
  std::filesystem::path dir_;
  std::function<const openscenario::TrafficBook*()> book_;
  std::optional<OutputFile> file_;
};

}  // namespace orch
