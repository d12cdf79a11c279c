#pragma once
// The metrics of a run (docs/evaluation.md): a RunObserver that measures every present
// vehicle actor (the ego and the scripted vehicles) each step against every other body the
// snapshot holds (actors and the nearby background vehicles), writes metrics.csv and, at the
// end, the per-actor summary into result.json. Criteria read this step's values through
// current().
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/output_file.hpp"
#include "map/lane_map.hpp"
#include "metrics/actor_metrics.hpp"
#include "metrics/pet.hpp"
#include "run/run_observer.hpp"

namespace orch::metrics {

class MetricsRecorder : public RunObserver {
 public:
  [[nodiscard]] const char* name() const override { return "metrics"; }
  // metrics.csv's header, generated from the metric table (metrics/metric_table.hpp).
  static const std::string& header();

  MetricsRecorder(const std::filesystem::path& csv, const LaneMap& lanes);

  void step(const StepView& view) override;
  void finish(RunResult& result) noexcept override;

  // This step's metrics, one per measured actor present.
  [[nodiscard]] const std::vector<ActorMetrics>& current() const { return current_; }
  [[nodiscard]] const ActorMetrics* current(sim::ActorId id) const;
  [[nodiscard]] std::vector<ActorSummary> summaries() const;

 private:
  [[nodiscard]] std::optional<double> departure(const sim::ActorState& a, double length, double width) const;

  OutputFile file_;
  const LaneMap& lanes_;
  std::unordered_map<std::string, int> lane_index_;  // SUMO lane id -> LaneMap index
  std::vector<ActorMetrics> current_;
  std::map<sim::ActorId, KinematicSample> last_sample_;
  std::map<sim::ActorId, Kinematics> last_kinematics_;
  std::map<sim::ActorId, ActorSummary> summaries_;
  TrajectoryBook trajectories_;  // every body seen, for PET at the end
  std::optional<double> last_time_;
};

}  // namespace orch::metrics
