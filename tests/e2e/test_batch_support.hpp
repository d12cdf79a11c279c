#pragma once
// Small batches for the batch tests: a logical scenario whose verdict each parameter set
// decides (so a test knows what every run must give) on a template that simulates about a
// second, and helpers to start a batch in the background and look at its folder.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"

namespace orch::test::batch {

// The ego drives on ALKS_Road; the run succeeds when the scenario ends at `q.end` s before
// the stop condition at 1 s fires (end 0.5 -> success, 2.0 -> failure), and cannot run
// (error) when `q.start` lies beyond the ego's route.
inline const char* kQuickTemplate = R"({
  "title": "Quick run ending at ${q.end} s",
  "map_id": "ALKS_Road",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": []},
  "scenario": {
    "opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": "${q.start}"}}, "next_scenes": [1]},
    "scenes": [],
    "ending_scenes": [{"scene_id": 1, "description": "ends at ${q.end} s",
      "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": "${q.end}"}}]}}]
  },
  "stop_conditions": {"or": [{"simulation_time": {"comparison": ">=", "value": 1.0}}]}
})";

inline const char* kQuickLogicalUuid = "0b1c2d3e-quick";

inline std::string quick_logical() {
  return std::string(R"({
  "uuid": ")") + kQuickLogicalUuid + R"(",
  "name": "Quick",
  "template": "quick.template.json",
  "parameter_space": {
    "q": {
      "end": {"type": "float", "unit": "s", "distribution": "choice", "choices": [0.5, 2.0]},
      "start": {"type": "int", "distribution": "constant", "value": 5}
    }
  }
})";
}

struct QuickSet {
  std::string uuid;
  double end;
  long long start;
};

// What a set must give.
inline std::string expected_verdict(const QuickSet& s) {
  if (s.start > 20000) return "error";
  return s.end < 1.0 ? "success" : "failure";
}

// Writes the logical scenario, its template and a hand-made parameter file into `dir`.
inline std::filesystem::path write_quick_batch(const TempDir& dir, const std::vector<QuickSet>& sets) {
  dir.write("quick.template.json", kQuickTemplate);
  const auto logical = dir.write(std::string("logical_") + kQuickLogicalUuid + ".json", quick_logical());
  nlohmann::ordered_json params;
  params["logical_uuid"] = kQuickLogicalUuid;
  params["created_at"] = "2026-11-22T10:00:00Z";
  params["parameters"] = nlohmann::ordered_json::object();
  long long seed = 100;
  for (const auto& s : sets)
    params["parameters"][s.uuid] = {{"created_at", "2026-11-22T10:00:00Z"},
                                    {"seed", seed++},
                                    {"sampled_values", {{"q", {{"end", s.end}, {"start", s.start}}}}},
                                    {"sumo_config", {{"map", "ALKS_Road"}, {"step", 0.05}, {"max_time", 5}}}};
  dir.write(std::string("logical_") + kQuickLogicalUuid + "_parameters.json", params.dump(2));
  return logical;
}

inline std::vector<QuickSet> mixed_sets(int count) {
  std::vector<QuickSet> out;
  for (int i = 0; i < count; ++i)
    out.push_back({"set-" + std::to_string(i), i % 3 == 1 ? 2.0 : 0.5, 5});
  return out;
}

// run id -> verdict from a batch folder's summary.json.
inline std::map<std::string, std::string> verdicts_of(const std::filesystem::path& summary) {
  std::map<std::string, std::string> out;
  const nlohmann::json j = read_json(summary);  // named: a range-for over a temporary's member dangles
  for (const auto& r : j["runs"]) out[r["run_id"].get<std::string>()] = r["verdict"].get<std::string>();
  return out;
}

inline std::string run_id_of(const std::string& set_uuid) { return std::string(kQuickLogicalUuid) + "_" + set_uuid; }

// Starts the orchestrator with `args` in the background, output to `log`. Returns its pid.
inline pid_t start_cli(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<std::string> argv{ORCH_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (auto& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::execv(cargv[0], cargv.data());
    ::_exit(127);
  }
  return pid;
}

// A process that is gone or a zombie no longer runs.
inline bool process_running(pid_t pid) {
  const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
  const auto close = stat.rfind(')');
  return close != std::string::npos && stat.size() > close + 2 && stat[close + 2] != 'Z';
}

// Processes whose command line mentions `text` (e.g. a batch folder): orphans of a batch.
inline std::vector<pid_t> processes_mentioning(const std::string& text) {
  std::vector<pid_t> out;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = slurp(entry.path() / "cmdline");
    std::string status = slurp(entry.path() / "status");
    if (status.find("State:\tZ") != std::string::npos) continue;
    for (auto& c : cmdline)
      if (c == '\0') c = ' ';
    if (cmdline.find(text) != std::string::npos) out.push_back(static_cast<pid_t>(std::stoi(name)));
  }
  return out;
}

}  // namespace orch::test::batch
