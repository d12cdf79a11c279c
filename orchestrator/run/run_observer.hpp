#pragma once
// The seam of the step loop: everything that watches a run (the trace writers, metrics,
// criteria) is a RunObserver. The runner calls begin() once before the first step, step()
// after every step the runtime judged, and finish() once at the end, whatever ended the run
// (also after an error), in the order the observers were added: a later observer may read
// what an earlier one computed in the same step. Observers see the run through ObservedRun,
// so that the same metrics and criteria watch both scenario languages.
#include <optional>
#include <string>
#include <vector>

#include "core/polyline.hpp"
#include "scenario_executor_engine/engine.hpp"

namespace orch {

struct RunResult;

// An actor as the observers measure it.
struct ObservedBody {
  std::string label;  // how outputs name it: the actor id ("0", "1", ...) or the entity's name
  double length = 0;
  double width = 0;
  ActorKind kind = ActorKind::Vehicle;
};

// What observers see of a run, whichever runtime moves its actors: the scene graph
// (engine::Engine, ScenarioExecutor files: run/engine_run.hpp) or the storyboard
// (OpenSCENARIO files: run/openscenario_observed.hpp).
class ObservedRun {
 public:
  virtual ~ObservedRun() = default;
  // The snapshot as judged (scripted ScenarioExecutor actors carry their commanded speed).
  [[nodiscard]] virtual const sim::WorldSnapshot& judged() const = 0;
  [[nodiscard]] virtual std::optional<sim::ActorId> ego() const = 0;
  // Null for an id the run does not have.
  [[nodiscard]] virtual std::optional<ObservedBody> body(sim::ActorId id) const = 0;
  // The line along which the actor's leader and follower are searched (its route); null: none.
  [[nodiscard]] virtual const Polyline* path_of(sim::ActorId id) const = 0;
  // Scenes are ScenarioExecutor's: an OpenSCENARIO run stays in scene 0 and has no visits;
  // its "ending" is the Storyboard's StopTrigger.
  [[nodiscard]] virtual int scene() const = 0;
  [[nodiscard]] virtual bool ending_reached() const = 0;
  [[nodiscard]] virtual const std::vector<engine::SceneVisit>& visits() const = 0;
  [[nodiscard]] virtual const std::vector<engine::Contact>& contacts() const = 0;
};

struct StepView {
  const ObservedRun& run;                     // run.judged(): the snapshot as judged
  const sim::WorldSnapshot& snapshot;      // as read from the simulator
  std::optional<sim::ActorId> plugin_driven;  // the actor an ego plug-in drove in this step
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // For result.json's timing.observers_s: where the step loop's own time goes.
  [[nodiscard]] virtual const char* name() const = 0;
  virtual void begin(const ObservedRun& /*run*/) {}
  virtual void step(const StepView& view) = 0;
  // The run has ended: flush, and add what this observer contributes to the result (it may
  // change the verdict). Must not throw: the result is written afterwards.
  virtual void finish(RunResult& /*result*/) noexcept {}
};

}  // namespace orch
