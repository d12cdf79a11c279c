#include "run/runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/scenario_format.hpp"
#include "run/ego_link.hpp"
#include "run/openscenario_format.hpp"
#include "run/run_format.hpp"
#include "run/run_log.hpp"
#include "run/run_observers.hpp"
#include "run/run_outcome.hpp"
#include "run/scenario_executor_format.hpp"

namespace orch {

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point from, Clock::time_point to) { return std::chrono::duration<double>(to - from).count(); }
double seconds_since(Clock::time_point t) { return seconds(t, Clock::now()); }

// A collision of the ego fails the test even when the scenario reached its own end
// afterwards (the run itself went on as scripted). Errors stay errors.
void judge_collision(const std::optional<std::string>& collision, RunResult& result) {
  if (!collision || result.verdict == Verdict::Error) return;
  result.reason = result.verdict == Verdict::Success ? *collision + " (" + result.reason + " afterwards)"
                                                     : *collision + "; " + result.reason;
  result.verdict = Verdict::Failure;
}

// The one step loop of every scenario language (run_format.hpp says what a language supplies).
RunResult run_format(const RunRequest& req, Simulator& sim, RunFormat& format) {
  const auto wall_start = Clock::now();
  std::optional<Clock::time_point> loop_start, loop_end;
  std::filesystem::create_directories(req.out_dir);
  RunLog log(req.out_dir / "run.log", req.echo);
  RunResult result = new_run_result(req, sim);
  log.note(fmt::format("orchestrator {} | {} {} | step {} s | seed {} | backend {}", ORCH_VERSION, format.input_kind(),
                       req.scenario_file, req.step, req.seed, sim.backend()));
  format.note_settings(log);
  // The step loop's observers (run_observer.hpp), in the order they see each step: the
  // language's own (its trace), then the measurement every run has. They refer to the
  // format's state, which outlives them.
  RunObservers observers;
  try {
    if (req.evaluation) result.evaluation = {req.evaluation->file, sha256_of_file(req.evaluation->file)};
    SimulatorConfig config;
    config.step = req.step;
    config.seed = req.seed;
    // Absolute paths: a SUMO joined with --connect resolves them in its own folder.
    config.log_file = std::filesystem::absolute(req.out_dir / "sumo.log").string();
    format.open(result, log, config);
    result.sumo_args = sumo_arguments(config);
    if (req.ego_link) log.note(req.ego_link->listen());
    sim.start(config);
    result.sumo_version = sim.version();
    format.add_observers(observers);
    observers.add_measurement(req, format.measured_lanes());
    observers.begin(format.observed());

    // The R157 reference driver drives the ego once the language has placed it (never with
    // a plug-in): it sees the scenario's commands and adds its own.
    std::optional<reference_driver::ReferenceEgo> reference_ego;
    auto drive_ego = [&](std::vector<sim::Command>& commands, const sim::WorldSnapshot* snap) {
      if (!reference_ego) reference_ego = format.take_reference_ego();
      if (!reference_ego) return;
      reference_ego->observe(commands);
      if (!snap) return;
      std::vector<std::string> noticed;
      for (auto& c : reference_ego->drive(*snap, format.tracked(), noticed)) commands.push_back(std::move(c));
      for (const auto& n : noticed) log.at(snap->time, n);
    };
    auto commands = format.start(result, log);
    drive_ego(commands, nullptr);
    sim.apply(commands);
    loop_start = Clock::now();
    while (true) {
      const auto before_step = Clock::now();
      sim.advance();
      result.timing.sumo_step_s += seconds_since(before_step);
      ++result.steps;
      const sim::WorldSnapshot snap = sim.read(format.tracked());
      const double t = format.take_step(snap, result, log);
      result.sim_time = t;
      observers.step(StepView{format.observed(), snap, plugin_driven_actor(req.ego_link, format.tracked())});
      if (!result.collision) result.collision = format.ego_collision(snap, t, log);
      if (format.ended()) break;
      if (req.max_time && t >= *req.max_time - 1e-9) {
        result.verdict = Verdict::Failure;
        result.reason = format.max_time_reason(*req.max_time);
        log.at(t, result.reason);
        break;
      }
      if (req.interrupted && req.interrupted->load()) {
        result.verdict = Verdict::Error;
        result.reason = fmt::format("interrupted at t={:.3f} s", t);
        log.at(t, result.reason);
        break;
      }
      commands = format.commands(snap, log);
      drive_ego(commands, &snap);
      sim.apply(commands);
      // The plug-in sees this step (a hand-over included) and acts before the world advances.
      if (req.ego_link) {
        const auto before_plugin = Clock::now();
        req.ego_link->exchange(snap.time);
        result.timing.plugin_s += seconds_since(before_plugin);
      }
    }
    loop_end = Clock::now();
    format.conclude(result, log);
  } catch (const ScenarioError& e) {
    observers.format_error(req, e.diagnostics());
    record_run_error(result, log);
  } catch (...) {
    record_run_error(result, log);
  }
  if (loop_start && !loop_end) loop_end = Clock::now();  // the loop ended by an exception
  format.finish(result);
  judge_collision(format.ego_collision_reason(), result);
  observers.finish(req, result);  // the trace's rows, metrics; criteria fold into the verdict
  if (req.ego_link) {
    req.ego_link->finish(to_string(result.verdict), result.reason);
    result.ego_plugin = req.ego_link->report();
    log.note(describe(*result.ego_plugin));
  }
  sim.close();
  result.wall_time_s = seconds_since(wall_start);
  if (!loop_start) loop_start = Clock::now();  // it never got to the first step
  if (!loop_end) loop_end = *loop_start;
  result.timing.start_s = seconds(wall_start, *loop_start);
  result.timing.orchestrator_s =
      std::max(0.0, seconds(*loop_start, *loop_end) - result.timing.sumo_step_s - result.timing.plugin_s);
  result.timing.finish_s = std::max(0.0, result.wall_time_s - seconds(wall_start, *loop_end));
  log.note(fmt::format("verdict {}: {} (simulated {:.2f} s in {} steps, {:.2f} s wall)", to_string(result.verdict),
                       result.reason, result.sim_time, result.steps, result.wall_time_s));
  write_result(req.out_dir, result);
  return result;
}

}  // namespace

RunResult run_scenario(const RunRequest& req, Simulator& sim) {
  // The one place where the language picks the runtime (the content decides, not the name).
  const auto format = detect_scenario_format(req.scenario_file) == ScenarioFormat::OpenScenario
                          ? openscenario_format(req)
                          : scenario_executor_format(req);
  return run_format(req, sim, *format);
}

}  // namespace orch
