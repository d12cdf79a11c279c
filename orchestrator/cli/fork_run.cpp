// `orchestrator run FILE --fork-with FILE2 --fork-out DIR2 ...`: the batch's way of running
// the parameter sets of one logical scenario that share a seed (docs/forking.md).
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "core/errors.hpp"
#include "core/utf8.hpp"
#include "evaluation/evaluation_file.hpp"
#include "core/files.hpp"
#include "core/scenario_format.hpp"
#include "openscenario/xosc_reader.hpp"
#include "run/fork_checkpoint.hpp"
#include "run/fork_group.hpp"
#include "run/runner.hpp"
#include "sumo/sumo_simulator.hpp"

namespace orch::cli {

namespace {

// --fork-param K:NAME=VALUE: the K-th variant's own --param values.
std::map<std::size_t, std::vector<std::string>> variant_parameters(const RunOptions& o) {
  std::map<std::size_t, std::vector<std::string>> out;
  for (const auto& text : o.fork_params) {
    const auto colon = text.find(':');
    std::size_t k = 0;
    const bool number = colon != std::string::npos && colon > 0 &&
                        std::all_of(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(colon),
                                    [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
    if (number && colon < 6) k = std::stoul(text.substr(0, colon));
    if (k < 1 || k > o.fork_with.size())
      throw OrchError(fmt::format("--fork-param {}: expected K:NAME=VALUE with K the number of a --fork-with variant "
                                  "(1 to {})", text, o.fork_with.size()));
    out[k].push_back(text.substr(colon + 1));
  }
  return out;
}

// --fork-at EVENT that no run of the group reached: each fork.json says whether its process
// took the checkpoint.
bool checkpoint_taken(const std::vector<RunRequest>& requests) {
  for (const auto& r : requests) {
    try {
      const auto j = nlohmann::json::parse(read_file(r.out_dir / "fork.json"));
      if (j.contains("checkpoint_s") && j["checkpoint_s"].is_number()) return true;
    } catch (const std::exception&) {
      // No fork.json: that run's process did not finish it.
    }
  }
  return false;
}

}  // namespace

int run_forked(const RunOptions& o, const RunRequest& request, const std::string& backend,
               const SumoBackendOptions& sumo_options) {
  if (o.fork_with.size() != o.fork_out.size())
    throw OrchError(fmt::format("--fork-with and --fork-out come in pairs: {} --fork-with, {} --fork-out",
                                o.fork_with.size(), o.fork_out.size()));
  if (is_evaluation_file(o.file)) throw OrchError("--fork-with: " + o.file + " is an evaluation file; give scenarios");
  if (o.video || o.gui || !o.connect.empty() || o.realtime)
    throw OrchError("--fork-with runs variants without a viewer: drop --video, --gui, --connect, --realtime");
  const auto own_parameters = variant_parameters(o);
  std::vector<RunRequest> requests{request};
  for (std::size_t i = 0; i < o.fork_with.size(); ++i) {
    RunRequest r = request;
    r.scenario_file = o.fork_with[i];
    r.out_dir = o.fork_out[i];
    // The first run's --param values, each replaced by the variant's own of the same name.
    if (const auto it = own_parameters.find(i + 1); it != own_parameters.end()) {
      if (detect_scenario_format(r.scenario_file) != ScenarioFormat::OpenScenario)
        throw OrchError("--fork-param sets OpenSCENARIO parameters: " + r.scenario_file + " is not an OpenSCENARIO file");
      for (const auto& [name, value] : openscenario::parse_parameter_overrides(it->second))
        r.parameter_overrides[name] = value;
    }
    requests.push_back(std::move(r));
  }
  std::optional<ForkCheckpoint> fork_at;
  if (o.fork_at) {
    fork_at = parse_fork_checkpoint(*o.fork_at);
    for (const auto& r : requests) check_checkpoint_event(*fork_at, r);
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
    results = run_fork_group(requests, *sim, fork_at);
  }
  int code = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    std::cout << "verdict: " << to_string(results[i].verdict) << " (" << valid_utf8(results[i].reason) << ")\n"
              << "results: " << (requests[i].out_dir / "result.json").string() << "\n";
    if (!o.no_report) announce_run_report(requests[i].out_dir);
    code = std::max(code, exit_code_for(results[i]));
  }
  if (fork_at && !fork_at->time_s && backend == "libsumo" && fork_refusal(requests, backend).empty() &&
      !checkpoint_taken(requests)) {
    // The runs are whole and exact (each as from t = 0); the request was not met.
    std::cerr << fmt::format("orchestrator: error: --fork-at {}: no variant reached the event before its run ended: "
                             "no checkpoint was taken (every run's outputs are those of its run from t = 0; fork.json "
                             "says so)\n",
                             fork_at->event);
    code = 2;
  }
  return code;
}

}  // namespace orch::cli
