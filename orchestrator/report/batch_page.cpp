#include "report/batch_page.hpp"

#include <fmt/format.h>

#include <map>
#include <set>

#include "core/files.hpp"
#include "report/html_page.hpp"

namespace orch::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// {"lead": {"speed": 60}} -> {"lead.speed": 60}
void flatten(const json& j, const std::string& prefix, json& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) flatten(*it, prefix.empty() ? it.key() : prefix + "." + it.key(), out);
  } else if (j.is_array()) {
    // The evaluation's per-actor summaries may come as a list: keyed by their actor.
    for (std::size_t i = 0; i < j.size(); ++i) {
      const json& e = j[i];
      const std::string key = e.is_object() && e.contains("actor")      ? e["actor"].dump()
                              : e.is_object() && e.contains("actor_id") ? e["actor_id"].dump()
                                                                        : std::to_string(i);
      flatten(e, prefix.empty() ? key : prefix + "." + key, out);
    }
  } else if (!prefix.empty() && (j.is_number() || j.is_boolean() || j.is_string())) {
    out[prefix] = j;
  }
}

json read_json_or_null(const fs::path& file) {
  if (!fs::exists(file)) return nullptr;
  try {
    return json::parse(read_file(file));
  } catch (const std::exception&) {
    return nullptr;  // an unreadable file leaves its part of the report empty
  }
}

// The scene graph of a bound scenario: scenes as nodes, next_scenes as edges.
json scene_graph(const json& scenario) {
  if (!scenario.is_object() || !scenario.contains("scenario") || !scenario["scenario"].is_object()) return nullptr;
  const json& s = scenario["scenario"];
  json nodes = json::array(), edges = json::array();
  auto add = [&](const json& scene, int id, bool ending) {
    nodes.push_back({{"id", id}, {"description", scene.value("description", "")}, {"ending", ending}});
    if (scene.contains("next_scenes") && scene["next_scenes"].is_array())
      for (const auto& n : scene["next_scenes"])
        if (n.is_number_integer()) edges.push_back({{"from", id}, {"to", n.get<int>()}});
  };
  if (s.contains("opening_scene") && s["opening_scene"].is_object()) add(s["opening_scene"], 0, false);
  for (const char* key : {"scenes", "ending_scenes"})
    if (s.contains(key) && s[key].is_array())
      for (const auto& scene : s[key])
        if (scene.is_object() && scene.contains("scene_id") && scene["scene_id"].is_number_integer())
          add(scene, scene["scene_id"].get<int>(), std::string(key) == "ending_scenes");
  return {{"nodes", nodes}, {"edges", edges}};
}

std::string relative_to_dir(const fs::path& target, const fs::path& base) {
  return fs::absolute(target).lexically_normal().lexically_relative(fs::absolute(base).lexically_normal()).string();
}

}  // namespace

json batch_report_data(const batch::BatchReport& report, const fs::path& out_dir) {
  const json summary = json::parse(batch::summary_json(report, out_dir));
  json data;
  data["kind"] = "batch";
  data["orchestrator_version"] = ORCH_VERSION;
  data["totals"] = summary["totals"];
  data["wall_time_s"] = summary["wall_time_s"];
  data["shards"] = summary["shards"];
  data["runs"] = json::array();
  std::map<std::string, std::set<std::string>> parameters;  // per logical scenario
  std::map<std::string, json> graphs;
  for (const auto& r : summary["runs"]) {
    if (r["verdict"] == "missing") continue;
    const fs::path dir = out_dir / r["run_dir"].get<std::string>();
    json run = {{"id", r["run_id"]},           {"logical_uuid", r["logical_uuid"]}, {"seed", r["seed"]},
                {"verdict", r["verdict"]},     {"reason", r["reason"]},             {"attempts", r["attempts"]},
                {"sim_time", r["sim_time"]},   {"wall_time_s", r["wall_time_s"]},  {"run_dir", r["run_dir"]}};
    json values = json::object();
    flatten(r["sampled_values"], "", values);
    for (auto it = values.begin(); it != values.end(); ++it) parameters[r["logical_uuid"]].insert(it.key());
    std::string text;
    for (auto it = values.begin(); it != values.end(); ++it)
      text += fmt::format("{}{}={}", text.empty() ? "" : ", ", it.key(),
                          it->is_number_float() ? fmt::format("{:.4g}", it->get<double>()) : it->is_string() ? it->get<std::string>() : it->dump());
    run["values"] = std::move(values);
    run["values_text"] = text;
    const json result = read_json_or_null(dir / "result.json");
    run["scenes"] = json::array();
    run["ending_scene"] = nullptr;
    run["metrics"] = json::object();
    if (result.is_object()) {
      if (result.contains("scenes") && result["scenes"].is_array())
        for (const auto& s : result["scenes"]) run["scenes"].push_back(s.value("scene_id", -1));
      run["ending_scene"] = result.value("ending_scene", json(nullptr));
      if (result.contains("metrics")) flatten(result["metrics"], "", run["metrics"]);
      run["preventable"] = result.value("preventable", json(nullptr));  // --reference-run
      // ... and as a value the parameter space can be coloured by: 1 = preventable.
      if (run["preventable"].is_string()) run["metrics"]["preventable"] = run["preventable"] == "preventable" ? 1 : 0;
    }
    run["report"] = fs::exists(dir / "report.html") ? json(relative_to_dir(dir / "report.html", out_dir)) : json(nullptr);
    if (!graphs.count(r["logical_uuid"])) {
      const json g = scene_graph(read_json_or_null(dir / "scenario.json"));
      if (!g.is_null()) graphs[r["logical_uuid"]] = g;
    }
    data["runs"].push_back(std::move(run));
  }
  data["logical_scenarios"] = json::array();
  for (const auto& s : summary["logical_scenarios"]) {
    const std::string uuid = s["logical_uuid"];
    json entry = s;
    entry["parameters"] = parameters.count(uuid) ? json(parameters[uuid]) : json::array();
    entry["graph"] = graphs.count(uuid) ? graphs[uuid] : json(nullptr);
    data["logical_scenarios"].push_back(std::move(entry));
  }
  return data;
}

fs::path write_batch_report(const batch::BatchReport& report, const fs::path& out_dir) {
  const fs::path out = out_dir / "report.html";
  write_file_atomically(out, html_page("Batch report", batch_report_script(), batch_report_data(report, out_dir)));
  return out;
}

}  // namespace orch::report
