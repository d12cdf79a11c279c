#pragma once
// Forked runs against their runs from t = 0 (docs/forking.md): run a run of a group again
// alone, from its execution trace's command, into its own folder, and compare every file
// byte for byte (wall-clock fields aside, as scripts/same_outputs/compare.py compares).
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"

namespace orch::test::forking {

namespace fs = std::filesystem;

// Files that say how the run was made, not what happened in it.
inline bool compared(const std::string& name) {
  return name != "fork.json" && name != "sumo.log" && name != "child.log" && name.rfind("attempt", 0) != 0 &&
         name != "scenario.json";
}

inline std::string normalised(const fs::path& file) {
  const std::string name = file.filename().string();
  if (name == "result.json") {
    auto j = read_json(file);
    j.erase("wall_time_s");
    j.erase("timing");
    return j.dump();
  }
  const std::string text = slurp(file);
  const std::regex wall(", [0-9.]+ s wall\\)");
  if (name == "run.log") return std::regex_replace(text, wall, ")");
  if (name == "report.html") {  // it embeds result.json and run.log
    const std::regex timing(R"("(wall_time_s":[-0-9.eE+]+|timing":\{[^{}]*(\{[^{}]*\}[^{}]*)*\}),?)");
    return std::regex_replace(std::regex_replace(text, timing, ""), std::regex(", [0-9.]+ s wall\\)"), ")");
  }
  return text;
}

// Every compared file of `a` and `b`, byte for byte after normalising; returns the differences.
inline std::vector<std::string> differences(const fs::path& a, const fs::path& b) {
  std::vector<std::string> out;
  std::set<std::string> names;
  for (const auto& d : {a, b})
    for (const auto& e : fs::directory_iterator(d))
      if (compared(e.path().filename().string())) names.insert(e.path().filename().string());
  for (const auto& n : names) {
    if (!fs::exists(a / n) || !fs::exists(b / n)) {
      out.push_back(n + " only in one");
      continue;
    }
    if (normalised(a / n) != normalised(b / n)) out.push_back(n);
  }
  return out;
}

// The command that runs the run in `run_dir` alone from t = 0, taken from its group's
// command (`run FIRST --out DIR ... --fork-with FILE --fork-out DIR [--fork-param K:N=V]
// ... [--fork-at X]`, the program's path first): this run's file and folder, and its --param
// values (the first run's, replaced by its own --fork-param ones).
inline std::vector<std::string> alone_command(const std::string& group_command, const fs::path& run_dir) {
  std::vector<std::string> command;
  std::istringstream words(group_command);
  for (std::string w; words >> w;) command.push_back(w);
  std::vector<std::string> with, outs, alone;
  std::map<std::string, std::string> params;
  std::vector<std::pair<std::size_t, std::string>> own;
  for (std::size_t i = 1; i < command.size(); ++i) {
    const std::string& a = command[i];
    if (a == "--fork-with") with.push_back(command[++i]);
    else if (a == "--fork-out") outs.push_back(command[++i]);
    else if (a == "--fork-at") ++i;
    else if (a == "--fork-param") {
      const std::string v = command[++i];
      own.emplace_back(std::stoul(v.substr(0, v.find(':'))), v.substr(v.find(':') + 1));
    } else if (a == "--param") {
      const std::string v = command[++i];
      params[v.substr(0, v.find('='))] = v.substr(v.find('=') + 1);
    } else {
      alone.push_back(a);
    }
  }
  std::size_t k = 0;  // 0: the group's first run; k: its k-th --fork-with variant
  for (std::size_t j = 0; j < outs.size(); ++j)
    if (fs::path(outs[j]).lexically_normal() == run_dir.lexically_normal()) k = j + 1;
  if (k > 0) {
    alone[1] = with[k - 1];
    alone[3] = run_dir.string();
    for (const auto& [variant, text] : own)
      if (variant == k) params[text.substr(0, text.find('='))] = text.substr(text.find('=') + 1);
  }
  for (const auto& [name, value] : params) alone.insert(alone.end(), {"--param", name + "=" + value});
  return alone;
}

// Runs the run of `trace` (an execution trace of the batch in `out`) again alone from t = 0,
// into its own folder (paths in the outputs stay the same), the forked outputs kept aside in
// `forked`, and returns the files that differ.
inline std::vector<std::string> rerun_alone(const fs::path& out, const nlohmann::json& trace, const fs::path& forked) {
  const fs::path run_dir = out / trace["outputs"]["run_dir"].get<std::string>();
  const auto alone = alone_command(trace["trace"]["implementation"]["command"].get<std::string>(), run_dir);
  fs::copy(run_dir, forked);
  for (const auto& f : fs::directory_iterator(run_dir))
    if (f.path().filename() != "scenario.json") fs::remove_all(f.path());
  const auto r = run_cli(alone);
  EXPECT_LE(r.exit_code, 1) << r.output;
  EXPECT_TRUE(fs::exists(forked / "trace.csv")) << forked;
  return differences(run_dir, forked);
}

}  // namespace orch::test::forking
