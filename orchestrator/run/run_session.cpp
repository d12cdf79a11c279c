#include "run/run_session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/scenario_format.hpp"
#include "run/openscenario_format.hpp"
#include "run/run_outcome.hpp"
#include "run/scenario_executor_format.hpp"

namespace orch {

namespace {

double seconds(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

// A collision of the ego fails the test even when the scenario reached its own end
// afterwards (the run itself went on as scripted). Errors stay errors.
void judge_collision(const std::optional<std::string>& collision, RunResult& result) {
  if (!collision || result.verdict == Verdict::Error) return;
  result.reason = result.verdict == Verdict::Success ? *collision + " (" + result.reason + " afterwards)"
                                                     : *collision + "; " + result.reason;
  result.verdict = Verdict::Failure;
}

}  // namespace

std::unique_ptr<RunFormat> format_for(const RunRequest& req) {
  // The one place where the language picks the runtime (the content decides, not the name).
  return detect_scenario_format(req.scenario_file) == ScenarioFormat::OpenScenario ? openscenario_format(req)
                                                                                    : scenario_executor_format(req);
}

RunSession::RunSession(const RunRequest& req, Simulator& sim)
    : req_(req), sim_(sim), format_(format_for(req)), wall_start_(Clock::now()) {
  std::filesystem::create_directories(req.out_dir);
  log_ = std::make_unique<RunLog>(req.out_dir / "run.log", req.echo);
  result_ = new_run_result(req, sim);
  log_->note(fmt::format("orchestrator {} | {} {} | step {} s | seed {} | backend {}", ORCH_VERSION,
                         format_->input_kind(), req.scenario_file, req.step, req.seed, sim.backend()));
  format_->note_settings(*log_);
}

RunSession::~RunSession() = default;

// Each phase of the loop as the one try block of the loop handled it: a scenario's own error
// goes to result.jsonl too; every error ends the run with verdict error.
template <typename F>
bool RunSession::guarded(F&& f) {
  if (done_) return false;
  try {
    f();
    return true;
  } catch (const ScenarioError& e) {
    observers_.format_error(req_, e.diagnostics());
    record_run_error(result_, *log_);
  } catch (...) {
    record_run_error(result_, *log_);
  }
  done_ = true;
  return false;
}

bool RunSession::open(SimulatorConfig& config) {
  return guarded([&] {
    if (req_.evaluation) result_.evaluation = {req_.evaluation->file, sha256_of_file(req_.evaluation->file)};
    config.step = req_.step;
    config.seed = req_.seed;
    // Absolute paths: a SUMO joined with --connect resolves them in its own folder.
    config.log_file = std::filesystem::absolute(req_.out_dir / "sumo.log").string();
    format_->open(result_, *log_, config);
    result_.sumo_args = sumo_arguments(config);
    if (req_.ego_link) log_->note(req_.ego_link->listen());
  });
}

bool RunSession::started() {
  return guarded([&] {
    result_.sumo_version = sim_.version();
    // The step loop's observers (run_observer.hpp), in the order they see each step: the
    // language's own (its trace), then the measurement every run has. They refer to the
    // format's state, which outlives them.
    format_->add_observers(observers_);
    observers_.add_measurement(req_, format_->measured_lanes());
    observers_.begin(format_->observed());
  });
}

// The R157 reference driver drives the ego once the language has placed it (never with a
// plug-in): it sees the scenario's commands and adds its own.
void RunSession::drive_ego(std::vector<sim::Command>& commands, const sim::WorldSnapshot* snap) {
  if (!reference_ego_) reference_ego_ = format_->take_reference_ego();
  if (!reference_ego_) return;
  reference_ego_->observe(commands);
  if (!snap) return;
  std::vector<std::string> noticed;
  for (auto& c : reference_ego_->drive(*snap, format_->tracked(), noticed)) commands.push_back(std::move(c));
  for (const auto& n : noticed) log_->at(snap->time, n);
}

std::optional<std::vector<sim::Command>> RunSession::first_commands() {
  std::vector<sim::Command> commands;
  if (!guarded([&] {
        commands = format_->start(result_, *log_);
        drive_ego(commands, nullptr);
        loop_start_ = Clock::now();
      }))
    return std::nullopt;
  return commands;
}

bool RunSession::take(const sim::WorldSnapshot& snap) {
  bool ended = false;
  const bool ok = guarded([&] {
    ++result_.steps;
    const double t = format_->take_step(snap, result_, *log_);
    result_.sim_time = t;
    observers_.step(StepView{format_->observed(), snap, plugin_driven_actor(req_.ego_link, format_->tracked())});
    if (!result_.collision) result_.collision = format_->ego_collision(snap, t, *log_);
    if (format_->ended()) {
      ended = true;
    } else if (t >= req_.max_time.value_or(kDefaultMaxTimeS) - 1e-9) {
      result_.verdict = Verdict::Failure;
      result_.reason = format_->max_time_reason(req_.max_time.value_or(kDefaultMaxTimeS));
      if (!req_.max_time) result_.reason += " (the limit without --max-time; give --max-time to run longer)";
      log_->at(t, result_.reason);
      ended = true;
    } else if (req_.interrupted && req_.interrupted->load()) {
      result_.verdict = Verdict::Error;
      result_.reason = fmt::format("interrupted at t={:.3f} s", t);
      log_->at(t, result_.reason);
      ended = true;
    }
    if (!ended) return;
    loop_end_ = Clock::now();
    format_->conclude(result_, *log_);
  });
  if (ok && ended) done_ = true;
  return done_;
}

std::optional<std::vector<sim::Command>> RunSession::next_commands(const sim::WorldSnapshot& snap) {
  std::vector<sim::Command> commands;
  if (!guarded([&] {
        commands = format_->commands(snap, *log_);
        drive_ego(commands, &snap);
      }))
    return std::nullopt;
  return commands;
}

void RunSession::fail() {
  guarded([] { throw; });
}

RunResult RunSession::finish(bool close_simulator) {
  done_ = true;
  if (loop_start_ && !loop_end_) loop_end_ = Clock::now();  // the loop ended by an exception
  format_->finish(result_);
  judge_collision(format_->ego_collision_reason(), result_);
  observers_.finish(req_, result_);  // the trace's rows, metrics; criteria fold into the verdict
  if (req_.ego_link) {
    req_.ego_link->finish(to_string(result_.verdict), result_.reason);
    result_.ego_plugin = req_.ego_link->report();
    log_->note(describe(*result_.ego_plugin));
  }
  if (close_simulator) sim_.close();
  result_.wall_time_s = seconds(wall_start_, Clock::now());
  if (!loop_start_) loop_start_ = Clock::now();  // it never got to the first step
  if (!loop_end_) loop_end_ = *loop_start_;
  result_.timing.start_s = seconds(wall_start_, *loop_start_);
  result_.timing.orchestrator_s = std::max(
      0.0, seconds(*loop_start_, *loop_end_) - result_.timing.sumo_step_s - result_.timing.plugin_s);
  result_.timing.finish_s = std::max(0.0, result_.wall_time_s - seconds(wall_start_, *loop_end_));
  log_->note(fmt::format("verdict {}: {} (simulated {:.2f} s in {} steps, {:.2f} s wall)", to_string(result_.verdict),
                         result_.reason, result_.sim_time, result_.steps, result_.wall_time_s));
  write_result(req_.out_dir, result_);
  return result_;
}

}  // namespace orch
