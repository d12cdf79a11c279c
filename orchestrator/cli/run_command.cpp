#include <atomic>
#include <csignal>
#include <iostream>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include <algorithm>

#include "cli/commands.hpp"
#include "core/errors.hpp"
#include "core/scenario_format.hpp"
#include "core/utf8.hpp"
#include "evaluation/evaluation_file.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/result_jsonl.hpp"
#include "run/paced_simulator.hpp"
#include "run/reference_run.hpp"
#include "run/runner.hpp"
#include "sumo/sumo_ego_control.hpp"
#include "sumo/sumo_simulator.hpp"
#include "traci_server/traci_ego_link.hpp"
#include "video/trace_video.hpp"

namespace orch::cli {

namespace {
std::atomic<bool> g_interrupted{false};
extern "C" void on_signal(int) { g_interrupted.store(true); }

// --gui and --connect need a SUMO process, i.e. the traci backend, which they then imply.
bool given(const RunOptions& o, const char* name) {
  return std::find(o.given.begin(), o.given.end(), name) != o.given.end();
}

// `run EVAL.yaml`: the scenario and its settings come from the evaluation file (options
// given on the command line win), the criteria go into the request. An invalid file ends
// here with verdict error, result.json and a result.jsonl whose last line says
// ScenarioFormatError; returns that exit status.
std::optional<int> prepare_evaluation(RunOptions& o, RunRequest& req) {
  const LoadedEvaluation loaded = load_evaluation(o.file);
  if (!loaded.file) {
    std::cerr << loaded.diagnostics.format();
    std::filesystem::create_directories(req.out_dir);
    write_format_error_jsonl(req.out_dir / "result.jsonl", loaded.diagnostics);
    RunResult result;
    result.reason = fmt::format("invalid evaluation file: {} error(s); first: {}", loaded.diagnostics.error_count(),
                                loaded.diagnostics.items().empty() ? "" : loaded.diagnostics.items().front().format());
    result.evaluation = {o.file, ""};
    write_result(req.out_dir, result);
    std::cout << "verdict: error (" << result.reason << ")\n";
    return exit_code_for(result);
  }
  const EvaluationFile& f = *loaded.file;
  req.scenario_file = f.scenario_file;
  if (f.step && !given(o, "--step")) req.step = *f.step;
  if (f.seed && !given(o, "--seed")) req.seed = *f.seed;
  if (f.max_time && !given(o, "--max-time")) req.max_time = *f.max_time;
  if (f.traffic && !given(o, "--traffic")) req.traffic = *f.traffic;
  if (f.backend && !given(o, "--backend")) o.backend = *f.backend;
  if (!f.local_map_path.empty()) req.map_dirs.insert(req.map_dirs.begin(), f.local_map_path);
  req.evaluation = EvaluationRequest{o.file, f.criteria, f.conditions, f.vehicle_model, o.jsonl_every};
  if (f.ego_model && !given(o, "--ego-model")) {
    req.ego_model = *f.ego_model;
    req.ego_model_given = true;
  }
  if (f.reference_run && !given(o, "--reference-run")) req.reference_run = *f.reference_run;
  // no_preventable_collision is judged against the reference run: it asks for one.
  for (const auto& c : f.criteria)
    if (c.type == "no_preventable_collision") req.reference_run = true;
  return std::nullopt;
}

std::string choose_backend(const RunOptions& o) {
  const bool needs_traci = o.gui || !o.connect.empty();
  if (o.backend.empty()) return needs_traci ? "traci" : "libsumo";
  if (o.backend == "libsumo" && needs_traci)
    throw std::invalid_argument("--gui and --connect run SUMO as a separate process: use --backend traci");
  return o.backend;
}
}  // namespace

int run_command(const RunOptions& o) {
  // Ctrl-C / SIGTERM end the run at the next step with verdict error; results are written.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  if (o.video) {
    if (const auto missing = video::missing_video_tools(); !missing.empty()) throw OrchError("run " + missing);
  }

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
  req.traffic = o.traffic;
  req.trace_background = o.trace_background;
  req.ego_entity = o.ego_entity;
  req.parameter_overrides = openscenario::parse_parameter_overrides(o.parameters);
  if (!o.parameters.empty() && detect_scenario_format(o.file) != ScenarioFormat::OpenScenario)
    throw OrchError("--param sets OpenSCENARIO parameters: " + o.file + " is not an OpenSCENARIO file");
  req.ssm = o.ssm;
  if (!o.ego_model.empty()) {
    req.ego_model.name = o.ego_model;
    req.ego_model_given = true;
  }
  req.reference_run = o.reference_run;

  req.controllers_off = o.controllers == "off";
  if (req.controllers_off) {  // the options that ask for a driver contradict it (the format checks the rest)
    for (const char* driver : {"--ego-model", "--reference-run"})
      if (given(o, driver))
        throw OrchError(fmt::format("--controllers off: every entity follows the storyboard; {} asks for a driver of "
                                    "the ego: give one or the other", driver));
    if (o.ego_port)
      throw OrchError("--controllers off: every entity follows the storyboard; --ego-port asks for a plug-in to drive "
                      "the ego: give one or the other");
  }

  RunOptions options = o;
  if (is_evaluation_file(o.file)) {
    const auto code = prepare_evaluation(options, req);
    if (code) return *code;
  }
  if (req.controllers_off && detect_scenario_format(req.scenario_file) != ScenarioFormat::OpenScenario)
    throw OrchError("--controllers off: OpenSCENARIO runs only (" + req.scenario_file +
                    " is a ScenarioExecutor scenario, whose ego SUMO or a plug-in drives)");
  const std::string backend = choose_backend(options);
  SumoBackendOptions sumo_options;
  sumo_options.gui = o.gui;
  sumo_options.connect = o.connect;
  sumo_options.reply_timeout = o.sumo_timeout;
  if (o.fork_at && o.fork_with.empty())
    throw OrchError("--fork-at: a checkpoint for variants: give them with --fork-with FILE --fork-out DIR");
  if (!o.fork_params.empty() && o.fork_with.empty())
    throw OrchError("--fork-param: the parameters of a variant: give the variants with --fork-with FILE --fork-out DIR");
  if (!o.fork_with.empty()) return run_forked(o, req, backend, sumo_options);
  const auto sumo = make_sumo_simulator(backend, sumo_options);
  std::optional<PacedSimulator> paced;
  if (options.realtime) paced.emplace(*sumo, *options.realtime);
  Simulator& sim = paced ? static_cast<Simulator&>(*paced) : *sumo;
  std::unique_ptr<EgoLink> ego;
  if (o.ego_port) {
    traci::EgoServerOptions eo;
    eo.address = o.ego_address;
    eo.port = *o.ego_port;
    eo.wait_s = o.ego_wait;
    eo.timeout_s = o.ego_timeout;
    eo.interrupted = &g_interrupted;
    ego = traci::make_traci_ego_link(eo, backend == "traci" ? make_ego_control_libtraci() : make_ego_control_libsumo());
    req.ego_link = ego.get();
  }
  const RunResult result = req.reference_run ? run_with_reference(req, sim, [&] {
    return make_sumo_simulator(backend, sumo_options);
  }) : run_scenario(req, sim);
  std::cout << "verdict: " << to_string(result.verdict) << " (" << valid_utf8(result.reason) << ")\n"
            << "results: " << (req.out_dir / "result.json").string() << "\n";
  if (o.video) announce_video(req.out_dir);
  if (!o.no_report) {
    announce_run_report(req.out_dir);
    if (req.reference_run && std::filesystem::exists(req.out_dir / "reference" / "result.json"))
      announce_run_report(req.out_dir / "reference");
  }
  return exit_code_for(result);
}

}  // namespace orch::cli
