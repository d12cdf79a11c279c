// `orchestrator run FILE --fork-with FILE2 --fork-out DIR2 ...`: the batch's way of running
// the parameter sets of one logical scenario that share a seed (docs/forking.md).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>

#include "cli/commands.hpp"
#include "core/errors.hpp"
#include "core/utf8.hpp"
#include "evaluation/evaluation_file.hpp"
#include "run/fork_group.hpp"
#include "run/runner.hpp"
#include "sumo/sumo_simulator.hpp"

namespace orch::cli {

int run_forked(const RunOptions& o, const RunRequest& request, const std::string& backend,
               const SumoBackendOptions& sumo_options) {
  if (o.fork_with.size() != o.fork_out.size())
    throw OrchError(fmt::format("--fork-with and --fork-out come in pairs: {} --fork-with, {} --fork-out",
                                o.fork_with.size(), o.fork_out.size()));
  if (is_evaluation_file(o.file)) throw OrchError("--fork-with: " + o.file + " is an evaluation file; give scenarios");
  if (o.video || o.gui || !o.connect.empty() || o.realtime)
    throw OrchError("--fork-with runs variants without a viewer: drop --video, --gui, --connect, --realtime");
  std::vector<RunRequest> requests{request};
  for (std::size_t i = 0; i < o.fork_with.size(); ++i) {
    RunRequest r = request;
    r.scenario_file = o.fork_with[i];
    r.out_dir = o.fork_out[i];
    requests.push_back(std::move(r));
  }
  std::vector<RunResult> results;
  if (const std::string refusal = fork_refusal(requests, backend); !refusal.empty()) {
    // Every variant still runs, each from t = 0, and says so.
    std::cerr << "orchestrator: not forking: " << refusal << "; every variant runs from t = 0\n";
    for (const auto& r : requests) {
      const auto sim = make_sumo_simulator(backend, sumo_options);
      results.push_back(run_scenario(r, *sim));
      write_unforked(r, refusal);
    }
  } else {
    const auto sim = make_sumo_simulator(backend, sumo_options);
    results = run_fork_group(requests, *sim, o.fork_at);
  }
  int code = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    std::cout << "verdict: " << to_string(results[i].verdict) << " (" << valid_utf8(results[i].reason) << ")\n"
              << "results: " << (requests[i].out_dir / "result.json").string() << "\n";
    if (!o.no_report) announce_run_report(requests[i].out_dir);
    code = std::max(code, exit_code_for(results[i]));
  }
  return code;
}

}  // namespace orch::cli
