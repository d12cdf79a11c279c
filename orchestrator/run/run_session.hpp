#pragma once
// One run of one scenario, cut into the phases of the one step loop (run/runner.cpp), so
// that the loop exists once whether a run has its SUMO to itself (run_scenario) or shares it
// with other variants of the same scenario for as long as they give the same commands
// (run/fork_group.hpp). Every phase catches the run's errors as the loop always did: the
// run then has verdict "error" and is done.
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "run/run_format.hpp"
#include "run/run_log.hpp"
#include "run/run_observers.hpp"
#include "run/run_result.hpp"
#include "run/runner.hpp"
#include "run/simulator.hpp"

namespace orch {

class RunSession {
 public:
  RunSession(const RunRequest& request, Simulator& simulator);
  ~RunSession();
  RunSession(const RunSession&) = delete;
  RunSession& operator=(const RunSession&) = delete;

  // Reads the inputs and fills in SUMO's configuration; false: the run failed (finish it).
  bool open(SimulatorConfig& config);
  // SUMO started (by this run or by the variant it shares SUMO with): the observers begin.
  bool started();
  // The first commands (actors placed, the reference driver's); nullopt: the run failed.
  std::optional<std::vector<sim::Command>> first_commands();
  // The step just simulated: true when the run has ended with it (its end, --max-time, an
  // interrupt or an error).
  bool take(const sim::WorldSnapshot& snapshot);
  // The commands for the next step; nullopt: the run failed.
  std::optional<std::vector<sim::Command>> next_commands(const sim::WorldSnapshot& snapshot);
  // The simulator failed for this run (a step, a read, applying its commands). Call it inside
  // the catch handler: the exception being handled is the run's error.
  void fail();
  // SUMO took a step for this run (its time, for result.json's timing).
  void add_step_time(double seconds) { result_.timing.sumo_step_s += seconds; }
  void add_plugin_time(double seconds) { result_.timing.plugin_s += seconds; }
  [[nodiscard]] const std::vector<sim::TrackedActor>& tracked() const { return format_->tracked(); }
  [[nodiscard]] bool done() const { return done_; }
  // --fork-at EVENT: the run's scenario has had the event (RunFormat::reached).
  [[nodiscard]] bool reached(const std::string& event) const { return format_->reached(event); }
  [[nodiscard]] const RunRequest& request() const { return req_; }
  [[nodiscard]] RunLog& log() { return *log_; }
  // Whatever ended the run: its result fields, the observers' files, result.json. Closes the
  // simulator when `close_simulator` (a shared one is closed by whoever owns it).
  RunResult finish(bool close_simulator);

 private:
  template <typename F>
  bool guarded(F&& f);
  void drive_ego(std::vector<sim::Command>& commands, const sim::WorldSnapshot* snapshot);

  using Clock = std::chrono::steady_clock;
  const RunRequest& req_;
  Simulator& sim_;
  std::unique_ptr<RunFormat> format_;
  Clock::time_point wall_start_;
  std::optional<Clock::time_point> loop_start_, loop_end_;
  std::unique_ptr<RunLog> log_;
  RunResult result_;
  RunObservers observers_;
  std::optional<reference_driver::ReferenceEgo> reference_ego_;
  bool done_ = false;
};

// The scenario language's part of the loop, chosen by the file's content.
std::unique_ptr<RunFormat> format_for(const RunRequest& request);

}  // namespace orch
