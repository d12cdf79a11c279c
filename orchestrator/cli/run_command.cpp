#include <atomic>
#include <csignal>
#include <iostream>

#include "cli/commands.hpp"
#include "run/runner.hpp"
#include "sumo/sumo_simulator.hpp"

namespace orch::cli {

namespace {
std::atomic<bool> g_interrupted{false};
extern "C" void on_signal(int) { g_interrupted.store(true); }
}  // namespace

int run_command(const RunOptions& o) {
  // Ctrl-C / SIGTERM end the run at the next step with verdict error; results are written.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  RunRequest req;
  req.scenario_file = o.file;
  req.out_dir = o.out;
  req.step = o.step;
  req.seed = o.seed;
  req.max_time = o.max_time;
  req.strict = o.strict;
  req.echo = !o.quiet;
  req.map_dirs.assign(o.common.map_dirs.begin(), o.common.map_dirs.end());
  req.catalog_file = o.common.catalog;
  req.interrupted = &g_interrupted;

  auto sim = make_libsumo_simulator();
  const RunResult result = run_scenario(req, *sim);
  std::cout << "verdict: " << result.verdict << " (" << result.reason << ")\n"
            << "results: " << (req.out_dir / "result.json").string() << "\n";
  return exit_code_for(result);
}

}  // namespace orch::cli
