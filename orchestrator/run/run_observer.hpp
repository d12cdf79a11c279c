#pragma once
// The seam of the step loop: everything that watches a run (the trace writers, metrics,
// criteria) is a RunObserver. The runner calls begin() once before the first step, step()
// after every step the engine judged, and finish() once at the end, whatever ended the run
// (also after an error), in the order the observers were added: a later observer may read
// what an earlier one computed in the same step.
#include <optional>

#include "engine/engine.hpp"

namespace orch {

struct RunResult;

struct StepView {
  const engine::Engine& engine;               // engine.judged(): the snapshot as judged
  const engine::WorldSnapshot& snapshot;      // as read from the simulator
  std::optional<scenario::ActorId> plugin_driven;  // the actor an ego plug-in drove in this step
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // For result.json's timing.observers_s: where the step loop's own time goes.
  [[nodiscard]] virtual const char* name() const = 0;
  virtual void begin(const engine::Engine& /*engine*/) {}
  virtual void step(const StepView& view) = 0;
  // The run has ended: flush, and add what this observer contributes to the result (it may
  // change the verdict). Must not throw: the result is written afterwards.
  virtual void finish(RunResult& /*result*/) noexcept {}
};

}  // namespace orch
