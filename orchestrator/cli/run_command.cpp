#include <atomic>
#include <csignal>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "cli/commands.hpp"
#include "run/paced_simulator.hpp"
#include "run/runner.hpp"
#include "sumo/sumo_ego_control.hpp"
#include "sumo/sumo_simulator.hpp"
#include "traci_server/traci_ego_link.hpp"

namespace orch::cli {

namespace {
std::atomic<bool> g_interrupted{false};
extern "C" void on_signal(int) { g_interrupted.store(true); }

// --gui and --connect need a SUMO process, i.e. the traci backend, which they then imply.
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

  const std::string backend = choose_backend(o);
  SumoBackendOptions sumo_options;
  sumo_options.gui = o.gui;
  sumo_options.connect = o.connect;
  sumo_options.reply_timeout = o.sumo_timeout;
  const auto sumo = make_sumo_simulator(backend, sumo_options);
  std::optional<PacedSimulator> paced;
  if (o.realtime) paced.emplace(*sumo, *o.realtime);
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
  const RunResult result = run_scenario(req, sim);
  std::cout << "verdict: " << result.verdict << " (" << result.reason << ")\n"
            << "results: " << (req.out_dir / "result.json").string() << "\n";
  return exit_code_for(result);
}

}  // namespace orch::cli
