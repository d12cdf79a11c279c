#pragma once
// `orchestrator search` (docs/search.md): an adaptive loop over the batch's runs. Each
// iteration proposes points of the parameter space (search_proposal.hpp), plans them as
// parameter sets of the logical scenario / variation, runs them exactly as a batch runs its
// runs (batch_runner.hpp: same folder layout, execution traces, summary, report), reads their
// result.json (search_objective.hpp) and proposes the next points.
//
// Folder: batch.json, runs/, executions/, summary.json ... as a batch, plus search.json (the
// options, every iteration's points, why they were chosen and the best so far, the critical
// runs, the boundary estimate) and search_parameters.json (every set run, a parameter file).
//
// Resume: run ids are numbered, and every proposal is a pure function of the seed and the
// results before it; `--resume DIR` replays the search from search.json's options, runs only
// runs without an execution trace, and goes on (a larger --budget extends a finished search).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "batch/batch_runner.hpp"

namespace orch::batch {

struct SearchOptions {
  std::string input;  // logical scenario or OpenSCENARIO variation
  std::string objective;
  std::string boundary;       // "" : falsification (minimise the objective)
  std::string method = "bo";  // bo, random, grid
  std::optional<int> budget;
  std::optional<long long> seed;
  std::vector<std::string> set_words;  // --set KEY=VALUE / KEY=LOW..HIGH
  std::optional<double> max_time;
  // Boundary: the smallest cell refined, as a fraction of each range (default 1/64).
  std::optional<double> resolution;
  // out, resume, jobs, timeout_s, retries, orchestrator, run_flags, wrapper, maps, catalog, ...
  BatchOptions batch;
};

// 0 the search finished, 3 interrupted (continue with --resume). Throws OrchError /
// ScenarioError for bad input before any run starts.
int run_search(const SearchOptions& options);

std::filesystem::path search_json_path(const std::filesystem::path& dir);

}  // namespace orch::batch
