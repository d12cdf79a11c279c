#pragma once
// The background traffic's part of a run's outputs (docs/outputs.md), beside trace.csv
// whose rows stay the scenario actors':
//   counts.csv      always: per step, how many background vehicles SUMO runs and how many
//                   of them are near an actor;
//   background.csv  with --trace-background only: one row per nearby background vehicle
//                   per step (the ones the engine sees, within 75 m of an actor), so that
//                   traces of dense runs stay small.
// Fixed precision, like trace.csv: the same run gives the same bytes.
#include <filesystem>
#include <optional>

#include "core/output_file.hpp"
#include "sim/world.hpp"
#include "run/run_observer.hpp"

namespace orch {

class TrafficTrace : public RunObserver {
 public:
  [[nodiscard]] const char* name() const override { return "traffic_trace"; }
  static constexpr const char* kCountsHeader = "time,background_vehicles,nearby_vehicles,waiting_over_60s";
  static constexpr const char* kBackgroundHeader = "time,vehicle_id,x,y,heading,speed,length,width";

  TrafficTrace(const std::filesystem::path& dir, bool background_rows);

  void record(const sim::WorldSnapshot& snapshot);
  void flush();
  [[nodiscard]] long long background_rows() const { return background_rows_; }

  void step(const StepView& view) override { record(view.snapshot); }
  void finish(RunResult& /*result*/) noexcept override { flush(); }

 private:
  OutputFile counts_;
  std::optional<OutputFile> background_;
  long long background_rows_ = 0;
  int steps_since_flush_ = 0;
};

}  // namespace orch
