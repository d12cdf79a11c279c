#pragma once
// What a scenario language supplies to the one run loop (run/runner.cpp): its opening, the
// per-step advance of its scenario logic, the commands it gives, its end condition and its
// own result fields. Everything else a run does exists once, in the loop: configuration,
// SUMO's start, --max-time and interrupts, the egos (SUMO, the R157 reference driver, an
// external plug-in), the observers, the ego's collision in the verdict, timing, result.json.
//
// The loop calls, in this order (each call after open() only when the ones before it
// returned normally; any of them may throw the project's typed errors, which end the run
// with verdict "error"):
//   open()                  inputs loaded and checked, SimulatorConfig filled in
//   add_observers()         after SUMO started: the language's own outputs (its trace)
//   observed()              from then on: the run as the observers see it
//   start()                 the first commands (actors placed)
//   per step: take_step()   the step just simulated: the scenario logic sees it
//             ego_collision()      (while the result has none)
//             ended()              the language's own end (then conclude())
//             commands()           the commands for the next step
//   finish()                whatever ended the run (also after an error): its result fields
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/world.hpp"
#include "map/lane_map.hpp"
#include "reference_driver/reference_ego.hpp"
#include "run/run_log.hpp"
#include "run/run_observer.hpp"
#include "run/run_observers.hpp"
#include "run/run_result.hpp"
#include "run/simulator.hpp"

namespace orch {

class RunFormat {
 public:
  virtual ~RunFormat() = default;

  // How the run log's first line names the input: "scenario", "OpenSCENARIO".
  [[nodiscard]] virtual const char* input_kind() const = 0;
  // Settings worth a run log line before the inputs are read (--param overrides).
  virtual void note_settings(RunLog& /*log*/) const {}
  // Reads and checks the inputs (result.json's scenario, map, net, title, ...) and fills in
  // `config`'s net, route files (background traffic) and extra arguments (--ssm); `config`
  // comes with the step, the seed and the log file.
  virtual void open(RunResult& result, RunLog& log, SimulatorConfig& config) = 0;
  // After SUMO started: the language's own observers (they see each step before the
  // measurement every run has). The lanes the metrics measure lane keeping on.
  virtual void add_observers(RunObservers& observers) = 0;
  [[nodiscard]] virtual const LaneMap& measured_lanes() const = 0;
  [[nodiscard]] virtual const ObservedRun& observed() const = 0;

  // The first commands: the actors placed.
  virtual std::vector<sim::Command> start(RunResult& result, RunLog& log) = 0;
  // The actors to read from the simulator (it may grow as entities appear).
  [[nodiscard]] virtual const std::vector<sim::TrackedActor>& tracked() const = 0;
  // The R157 reference driver once it drives the ego (--ego-model r157), handed to the loop
  // the first time it is asked after the language placed the ego; nullopt before, and when
  // another model drives.
  virtual std::optional<reference_driver::ReferenceEgo> take_reference_ego() = 0;

  // The step just simulated, as read: the scenario logic sees it (its events go to the log
  // and the result). Returns the step's time as the run records it.
  virtual double take_step(const sim::WorldSnapshot& snapshot, RunResult& result, RunLog& log) = 0;
  // The ego's first collision, if it happened by this step.
  virtual std::optional<CollisionFact> ego_collision(const sim::WorldSnapshot& snapshot, double time,
                                                     RunLog& log) = 0;
  // The scenario's own end (an ending scene, a stop condition, the StopTrigger).
  [[nodiscard]] virtual bool ended() const = 0;
  // Why --max-time ended the run, in the language's words.
  [[nodiscard]] virtual std::string max_time_reason(double max_time) const = 0;
  // The commands for the next step (the reference driver's are added by the loop).
  virtual std::vector<sim::Command> commands(const sim::WorldSnapshot& snapshot, RunLog& log) = 0;
  // --fork-at EVENT (run/fork_checkpoint.hpp): whether the event has happened by now, as of
  // the commands just given: "scene:N" entered, a storyboard element of that name started.
  [[nodiscard]] virtual bool reached(const std::string& /*event*/) const { return false; }
  // The step loop has ended without an error: the verdict of the language's own end.
  virtual void conclude(RunResult& result, RunLog& log) = 0;

  // Whatever ended the run: the language's result fields (actors, scenes, contacts, ...).
  virtual void finish(RunResult& result) = 0;
  // A collision of the ego that fails the test, as the verdict's reason says it.
  [[nodiscard]] virtual std::optional<std::string> ego_collision_reason() const = 0;
};

}  // namespace orch
