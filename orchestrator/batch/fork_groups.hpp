#pragma once
// Which runs of a batch share their common prefix (docs/forking.md): the parameter sets of
// one logical scenario (a template, or an OpenSCENARIO variation: its sets differ in --param
// values of one file) that run with the same seed and the same sumo_config. They run as one
// child `orchestrator run FIRST --fork-with OTHER --fork-out DIR [--fork-param K:NAME=VALUE]
// ...`, which shares one libsumo simulation between them while their commands are equal.
#include <cstddef>
#include <optional>
#include <vector>

#include "batch/batch_plan.hpp"

namespace orch::batch {

// `batch --fork`: every set of a logical scenario (a variation too: its sets' values are in
// the set, the seed is SUMO's only) runs with the seed of its first set (recorded as the
// set's seed in its execution trace), so that they can share. Without it only sets that
// already share a seed do.
void use_one_seed_per_logical(BatchPlan& plan);

// The runs (indices into plan.runs) grouped as above, in plan order; a run that shares with
// no other is a group of one. Only the runs in `pending`. A group's processes run one at a
// time, so while there are fewer groups than `jobs` the largest is halved (each half runs the
// prefix once): every core gets work.
std::vector<std::vector<std::size_t>> fork_groups(const BatchPlan& plan, const std::vector<std::size_t>& pending,
                                                  bool enabled, int jobs);

}  // namespace orch::batch
