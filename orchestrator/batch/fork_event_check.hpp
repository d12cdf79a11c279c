#pragma once
// `batch --fork-at EVENT` (docs/forking.md): the event checked before any run, against the
// first set of every logical scenario of the plan: a template's bound scenario (its scenes)
// or a variation's scenario with that set's values (its storyboard elements). Each group's
// process checks its own variants again (run/fork_checkpoint.hpp).
#include "batch/batch_plan.hpp"
#include "core/fork_checkpoint.hpp"

namespace orch::batch {

// Throws OrchError (the event, the file, what it has, "did you mean") when a logical
// scenario of `plan` has no such event. A time, or a scenario that does not load, passes
// (the runs report their own errors).
void check_fork_event(const BatchPlan& plan, const ForkCheckpoint& checkpoint);

}  // namespace orch::batch
