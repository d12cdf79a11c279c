#include "run/run_result.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "json/json_text.hpp"
#include "metrics/metric_table.hpp"

namespace orch {

namespace {
const char* kind_name(engine::EventKind k) {
  switch (k) {
    case engine::EventKind::Scene: return "scene";
    case engine::EventKind::Action: return "action";
    case engine::EventKind::Warning: return "warning";
    case engine::EventKind::Info: return "info";
    case engine::EventKind::Storyboard: return "storyboard";
  }
  return "info";
}

// A contact's body: scenario actors by their actor id (a number), background vehicles by
// their SUMO id (a string).
nlohmann::ordered_json body_json(const std::string& name) {
  const bool digits = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
  return digits ? nlohmann::ordered_json(std::stoi(name)) : nlohmann::ordered_json(name);
}

// Metric values are rounded to 1e-6 so that the text does not depend on the last bits of a
// floating-point sum.
double rounded(double v) { return std::round(v * 1e6) / 1e6; }
nlohmann::ordered_json optional_json(const std::optional<double>& v) {
  return v ? nlohmann::ordered_json(rounded(*v)) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json extreme_json(const std::optional<metrics::Extreme>& e, bool with_partner) {
  if (!e) return nullptr;
  nlohmann::ordered_json j{{"value", rounded(e->value)}, {"time", rounded(e->time)}};
  if (with_partner) j["partner"] = body_json(e->partner);
  return j;
}

// Each actor's summaries, keyed and ordered as the metric table says (metrics/metric_table.hpp).
nlohmann::ordered_json metrics_json(const std::vector<metrics::ActorSummary>& all) {
  const auto& table = metrics::metric_table();
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& s : all) {
    nlohmann::ordered_json one = nlohmann::ordered_json::object();
    for (const std::size_t i : metrics::summary_rows()) {
      const metrics::MetricDef& d = table[i];
      const metrics::ActorSummary::Row row = i < s.rows.size() ? s.rows[i] : metrics::ActorSummary::Row{};
      one[std::string(d.summary_key)] = d.summary == metrics::Summary::SecondsPositive
                                            ? nlohmann::ordered_json(rounded(row.seconds))
                                            : extreme_json(row.extreme, d.has_partner());
    }
    j[s.label.empty() ? std::to_string(s.actor) : s.label] = std::move(one);
  }
  return j;
}

// The storyboard's TrafficActions: totals over all of them, then each (docs/outputs.md).
nlohmann::ordered_json storyboard_traffic_json(const std::vector<TrafficActionRecord>& actions) {
  if (actions.empty()) return nullptr;
  int spawned = 0, removed = 0, left = 0, not_inserted = 0, active = 0, removed_background = 0;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& a : actions) {
    spawned += a.spawned;
    // A vehicle a sink removed counts in its owner's `removed` and in the sink's: once here.
    if (a.kind == "sink") removed_background += a.removed_background;
    else removed += a.removed;
    left += a.left;
    not_inserted += a.not_inserted;
    active += a.active_at_end;
    nlohmann::ordered_json e{{"kind", a.kind},
                             {"name", a.name},
                             {"label", a.label},
                             {"vehicles", a.vehicles.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(a.vehicles)},
                             {"started", a.started},
                             {"stopped", optional_json(a.stopped)},
                             {"spawned", a.spawned},
                             {"removed", a.removed},
                             {"left", a.left},
                             {"not_inserted", a.not_inserted},
                             {"active_at_end", a.active_at_end}};
    if (a.kind == "sink") e["removed_background"] = a.removed_background;
    list.push_back(std::move(e));
  }
  return {{"spawned", spawned},
          {"removed", removed + removed_background},
          {"removed_background", removed_background},
          {"left", left},
          {"not_inserted", not_inserted},
          {"active_at_end", active},
          {"actions", std::move(list)}};
}

nlohmann::ordered_json file_json(const InputFile& f) {
  return {{"path", f.path}, {"sha256", f.sha256}};
}
}  // namespace

std::string to_json(const RunResult& r) {
  nlohmann::ordered_json j;
  j["verdict"] = to_string(r.verdict);
  j["reason"] = r.reason;
  j["sim_time"] = r.sim_time;
  j["steps"] = r.steps;
  j["title"] = r.title;
  j["description"] = r.description;
  j["scenes"] = nlohmann::ordered_json::array();
  for (const auto& s : r.scenes)
    j["scenes"].push_back({{"scene_id", s.id}, {"description", s.description}, {"enter_time", s.enter_time}});
  j["ending_scene"] = r.ending_scene ? nlohmann::ordered_json(*r.ending_scene) : nlohmann::ordered_json(nullptr);
  j["seed"] = r.seed;
  j["step"] = r.step;
  j["max_time"] = r.max_time ? nlohmann::ordered_json(*r.max_time) : nlohmann::ordered_json(nullptr);
  j["backend"] = r.backend;
  j["sumo_version"] = r.sumo_version;
  j["orchestrator_version"] = ORCH_VERSION;
  j["map_id"] = r.map_id;
  j["inputs"] = {{"scenario", file_json(r.scenario)}, {"waypoints", file_json(r.waypoints)}, {"net", file_json(r.net)}};
  if (!r.evaluation.path.empty()) j["inputs"]["evaluation"] = file_json(r.evaluation);
  j["inputs"]["traffic"] = r.traffic_file.path.empty() ? nlohmann::ordered_json(nullptr) : file_json(r.traffic_file);
  j["traffic"] = r.traffic;
  j["sumo_args"] = r.sumo_args;
  j["events"] = nlohmann::ordered_json::array();
  for (const auto& e : r.events) {
    nlohmann::ordered_json event{{"time", e.time}, {"kind", kind_name(e.kind)}, {"text", e.text}};
    event["actor"] = e.actor ? nlohmann::ordered_json(*e.actor) : nlohmann::ordered_json(nullptr);
    event["scene"] = e.scene ? nlohmann::ordered_json(*e.scene) : nlohmann::ordered_json(nullptr);
    j["events"].push_back(std::move(event));
  }
  j["warnings"] = r.warnings;
  j["collisions"] = nlohmann::ordered_json::array();
  for (const auto& c : r.collisions) {
    j["collisions"].push_back({{"time", c.time},
                               {"between", {body_json(c.a), body_json(c.b)}},
                               {"positions", {{c.position_a.x(), c.position_a.y()}, {c.position_b.x(), c.position_b.y()}}},
                               {"source", c.source},
                               {"counted", c.counted},
                               {"sumo_type", c.sumo_type}});
  }
  j["lane_change_conflicts"] = nlohmann::ordered_json::array();
  for (const auto& c : r.lane_change_conflicts) {
    j["lane_change_conflicts"].push_back(
        {{"time", c.time},
         {"actor", c.actor},
         {"vehicle", c.vehicle},
         {"target_route", c.target_route},
         {"gap", c.gap},
         {"vehicle_is", c.vehicle_ahead ? "ahead" : "behind"},
         {"time_gap", std::isfinite(c.time_gap) ? nlohmann::ordered_json(c.time_gap) : nlohmann::ordered_json(nullptr)},
         {"positions", {{c.actor_position.x(), c.actor_position.y()}, {c.vehicle_position.x(), c.vehicle_position.y()}}}});
  }
  j["hand_overs"] = nlohmann::ordered_json::array();
  for (const auto& h : r.hand_overs) {
    nlohmann::ordered_json e{{"time", h.time}, {"hand_over", h.action.hand_over}};
    if (h.action.throttle) e["throttle"] = *h.action.throttle;
    if (h.action.brake) e["brake"] = *h.action.brake;
    if (h.action.steer) e["steer"] = *h.action.steer;
    j["hand_overs"].push_back(e);
  }
  j["ego_plugin"] = nullptr;
  if (r.ego_plugin) {
    const EgoLinkReport& e = *r.ego_plugin;
    j["ego_plugin"] = {{"listen", e.listen},
                       {"peer", e.peer.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(e.peer)},
                       {"client", e.client.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(e.client)},
                       {"order", e.order ? nlohmann::ordered_json(*e.order) : nlohmann::ordered_json(nullptr)},
                       {"connected_at", e.connected_at ? nlohmann::ordered_json(*e.connected_at) : nlohmann::ordered_json(nullptr)},
                       {"steps_driven", e.steps_driven},
                       {"end", e.end},
                       {"commands", e.commands}};
  }
  j["actors"] = nlohmann::ordered_json::array();
  for (const auto& a : r.actors)
    j["actors"].push_back({{"actor_id", a.id}, {"sumo_id", a.sumo_id}, {"model_id", a.model_id},
                           {"description", a.description}, {"color", a.color}, {"length", a.length},
                           {"width", a.width}, {"ego", a.ego}});
  j["metrics"] = metrics_json(r.metrics);
  j["criteria"] = nlohmann::ordered_json::array();
  for (const auto& c : r.criteria)
    j["criteria"].push_back({{"name", c.name},
                             {"actor", c.actor ? nlohmann::ordered_json(*c.actor) : nlohmann::ordered_json(nullptr)},
                             {"metric", c.metric},
                             {"expected", c.expected},
                             {"actual", optional_json(c.actual)},
                             {"at_time", optional_json(c.at_time)},
                             {"success", c.success}});
  j["ego_model"] = r.ego_model;
  if (!r.controllers.empty()) j["controllers"] = r.controllers;
  auto collision_json = [](const std::optional<CollisionFact>& c) {
    if (!c) return nlohmann::ordered_json(nullptr);
    return nlohmann::ordered_json{{"with", c->with}, {"time", c->time}, {"relative_speed", optional_json(c->relative_speed)}};
  };
  j["collision"] = collision_json(r.collision);
  if (r.ego_min_gap || r.ego_min_ttc)
    j["ego_exposure"] = {{"min_gap", optional_json(r.ego_min_gap)}, {"min_ttc", optional_json(r.ego_min_ttc)}};
  j["reference_run"] = nullptr;
  if (r.reference_run) {
    const ReferenceRunRecord& ref = *r.reference_run;
    j["reference_collision"] = collision_json(ref.reference_collision);
    j["preventable"] = ref.outcome;
    j["reference_run"] = {{"dir", ref.dir},
                          {"verdict", ref.verdict},
                          {"outcome", ref.outcome},
                          {"min_ttc", optional_json(ref.min_ttc)},
                          {"reference_min_ttc", optional_json(ref.reference_min_ttc)},
                          {"min_gap", optional_json(ref.min_gap)},
                          {"reference_min_gap", optional_json(ref.reference_min_gap)}};
  }
  j["storyboard_traffic"] = storyboard_traffic_json(r.storyboard_traffic);
  j["monitors"] = nullptr;
  for (const auto& [name, value] : r.monitors) j["monitors"][name] = value;
  j["trace_rows"] = r.trace_rows;
  j["wall_time_s"] = r.wall_time_s;
  j["timing"] = {{"start_s", r.timing.start_s},
                 {"sumo_step_s", r.timing.sumo_step_s},
                 {"orchestrator_s", r.timing.orchestrator_s},
                 {"plugin_s", r.timing.plugin_s},
                 {"finish_s", r.timing.finish_s}};
  j["timing"]["observers_s"] = nlohmann::ordered_json::object();
  for (const auto& [name, s] : r.timing.observers_s) j["timing"]["observers_s"][name] = s;
  j["outputs"] = {{"trace", "trace.csv"}, {"log", "run.log"}, {"sumo_log", "sumo.log"}, {"metrics", "metrics.csv"}};
  if (!r.storyboard_traffic.empty()) j["outputs"]["traffic_actions"] = "traffic_actions.csv";
  return json_text(j, 2) + "\n";
}

void write_result(const std::filesystem::path& dir, const RunResult& r) {
  write_file_atomically(dir / "result.json", to_json(r));
}

int exit_code_for(const RunResult& r) {
  switch (r.verdict) {
    case Verdict::Success: return 0;
    case Verdict::Failure: return 1;
    case Verdict::Error: return 2;
  }
  return 2;
}

}  // namespace orch
