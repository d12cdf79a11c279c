#pragma once
// Variants of one scenario (a batch's parameter sets bound into one template, run with the
// same seed and options) run their common prefix once: they share one libsumo simulation
// for as long as they give SUMO the same commands, and the process fork()s where they part.
//
// Why this is exact: each variant runs its own scenario runtime, reference driver and
// observers over every step from t = 0 (run/run_session.hpp), exactly as run_scenario would.
// SUMO's next state depends only on its state and the commands it is given; while the
// commands of two variants are equal (field by field, bit for bit: sim/world.hpp's
// operator==) and so is the list of actors they read, their SUMO worlds are the same world,
// so sharing it changes nothing they see. The step where their commands first differ is
// where the process forks: the child inherits SUMO's whole memory (libsumo runs in-process),
// which is exactly the state a run from t = 0 would have there. No saved state, no guess of
// which parameter is read when: the runtimes themselves say when they part.
// (SUMO 1.15's saveState/loadState is not exact for our runs: docs/forking.md.)
//
// Each run folder gets fork.json: from which step on the run had SUMO to itself, and with
// whom it shared the steps before. Everything else in the folder is what a run from t = 0
// writes (result.json's wall-clock timing aside).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/fork_checkpoint.hpp"
#include "run/run_result.hpp"
#include "run/runner.hpp"
#include "run/simulator.hpp"

namespace orch {

// Why the requests cannot share a simulation (an ego plug-in, a backend that does not run
// SUMO in this process); empty when they can.
std::string fork_refusal(const std::vector<RunRequest>& requests, const std::string& backend);

// Runs every request, sharing `simulator` (libsumo) as described above, and returns once
// every run has finished (the forked processes too, one at a time: a group uses one core).
// Returns the results of the runs in their order as their result.json says them.
// `fork_at` (--fork-at): a checkpoint requested by the user: at the first step at or after
// that SUMO time, or at the first step after which a variant (of the ones still sharing) has
// had the event (a scene entered, a storyboard element started: the commands that follow
// from it given, not yet simulated), every variant continues in a process of its own, even
// variants whose commands are still the same. Exactness comes first: variants whose commands
// part before it still part where they part (nothing can make them share a world they do
// not share), and their fork.json says so in `warning`. The event is checked against the
// scenario beforehand (run/fork_checkpoint.hpp), not here.
std::vector<RunResult> run_fork_group(const std::vector<RunRequest>& requests, Simulator& simulator,
                                      const std::optional<ForkCheckpoint>& fork_at = std::nullopt);

// fork.json of a run that was to share and ran from t = 0 instead, and why.
void write_unforked(const RunRequest& request, const std::string& why);

}  // namespace orch
