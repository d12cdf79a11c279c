#include "run/runner.hpp"

#include <chrono>

#include "run/run_session.hpp"

namespace orch {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

// The one step loop of every scenario language (run_format.hpp says what a language
// supplies; run_session.hpp each phase of a run). run/fork_group.cpp runs the same phases
// for variants that share SUMO.
RunResult run_scenario(const RunRequest& req, Simulator& sim) {
  RunSession run(req, sim);
  // A failure of the simulator (or of the plug-in) ends the run with verdict error.
  auto simulator = [&](auto&& f) {
    try {
      f();
      return true;
    } catch (...) {
      run.fail();
      return false;
    }
  };
  // Applies a step's commands; the plug-in sees the step (a hand-over included) and acts
  // before the world advances.
  auto apply = [&](const std::vector<sim::Command>& commands, const sim::WorldSnapshot* snap) {
    return simulator([&] {
      sim.apply(commands);
      if (!req.ego_link || !snap) return;
      const auto before_plugin = Clock::now();
      req.ego_link->exchange(snap->time);
      run.add_plugin_time(seconds_since(before_plugin));
    });
  };
  SimulatorConfig config;
  if (run.open(config) && simulator([&] { sim.start(config); }) && run.started()) {
    auto commands = run.first_commands();
    bool going = commands && apply(*commands, nullptr);
    while (going) {
      sim::WorldSnapshot snap;
      going = simulator([&] {
        const auto before_step = Clock::now();
        sim.advance();
        run.add_step_time(seconds_since(before_step));
        snap = sim.read(run.tracked());
      });
      if (!going || run.take(snap)) break;
      commands = run.next_commands(snap);
      going = commands && apply(*commands, &snap);
    }
  }
  return run.finish(true);
}

}  // namespace orch
