#include "batch/batch_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "batch/batch_metrics_csv.hpp"
#include "batch/identifiers.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/utf8.hpp"
#include "json/json_text.hpp"

namespace orch::batch {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

std::string value_text(const nlohmann::json& v) {
  if (v.is_number_float()) return fmt::format("{:.4g}", v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return json_text(v);
}

// "ego.speed=62.5, lead.gap=40"
std::string values_text(const nlohmann::json& grouped) {
  std::string out;
  for (auto g = grouped.begin(); g != grouped.end(); ++g)
    if (g->is_object())
      for (auto p = g->begin(); p != g->end(); ++p)
        out += fmt::format("{}{}.{}={}", out.empty() ? "" : ", ", g.key(), p.key(), value_text(*p));
  return out;
}

std::string relative_to(const fs::path& target, const fs::path& base) {
  return fs::absolute(target).lexically_normal().lexically_relative(fs::absolute(base).lexically_normal()).string();
}

std::string label(const PlannedEntry& e) { return e.name.empty() ? e.logical_uuid : e.name; }

// Per logical scenario, in the order first planned.
struct Group {
  std::string logical_uuid;
  std::string name;
  std::vector<const PlannedEntry*> runs;
};

std::vector<Group> groups_of(const BatchReport& report) {
  std::vector<Group> groups;
  for (const auto& e : report.planned) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.logical_uuid == e.logical_uuid; });
    if (it == groups.end()) {
      groups.push_back({e.logical_uuid, label(e), {}});
      it = std::prev(groups.end());
    }
    it->runs.push_back(&e);
  }
  return groups;
}

BatchReport::Totals count(const BatchReport& report, const std::vector<const PlannedEntry*>& runs) {
  BatchReport::Totals t;
  for (const auto* e : runs) {
    const auto it = report.done.find(e->id);
    if (it == report.done.end()) ++t.missing;
    else if (it->second.verdict == "success") ++t.success;
    else if (it->second.verdict == "failure") ++t.failure;
    else ++t.error;
  }
  return t;
}

std::string truncated(const std::string& s, std::size_t n) { return s.size() <= n ? s : s.substr(0, n - 3) + "..."; }

}  // namespace

BatchReport::Totals BatchReport::planned_totals() const {
  std::vector<const PlannedEntry*> all;
  for (const auto& e : planned) all.push_back(&e);
  return count(*this, all);
}

BatchReport::Totals BatchReport::totals() const {
  Totals t = planned_totals();
  // Runs of shards not given to a merge are missing too.
  if (total_runs > planned.size()) t.missing += total_runs - planned.size();
  return t;
}

BatchReport collect_report(const std::vector<fs::path>& batch_dirs) {
  BatchReport report;
  std::set<std::string> planned_ids;
  std::optional<std::size_t> total;
  for (const auto& dir : batch_dirs) {
    const Manifest m = read_manifest(dir);
    report.batch_dirs.push_back(dir);
    if (m.shard) report.shards.push_back(m.shard->text());
    if (total && *total != m.total_runs)
      throw OrchError(fmt::format("{} belongs to another batch: {} runs in all, the others have {}", dir.string(),
                                  m.total_runs, *total));
    total = m.total_runs;
    for (const auto& e : m.runs) {
      if (!planned_ids.insert(e.id).second)
        throw OrchError(fmt::format("run {} is planned in two of the folders (the second: {}): merge each shard once",
                                    e.id, dir.string()));
      report.planned.push_back(e);
    }
    for (const auto& e : m.runs) {
      const fs::path file = execution_trace_path(dir, e.id);
      if (!fs::exists(file)) continue;
      ExecutionSummary s = read_execution_summary(file);
      if (s.run_id != e.id)
        throw OrchError(fmt::format("{} records run {}, expected {}", file.string(), s.run_id, e.id));
      report.done_in[e.id] = dir;
      report.done.emplace(e.id, std::move(s));
    }
  }
  report.total_runs = total.value_or(0);
  return report;
}

std::string summary_json(const BatchReport& report, const fs::path& out_dir) {
  const auto t = report.totals();
  ordered_json j;
  j["created_at"] = utc_timestamp();
  j["batch_dirs"] = ordered_json::array();
  for (const auto& d : report.batch_dirs) j["batch_dirs"].push_back(relative_to(d, out_dir));
  j["shards"] = report.shards;
  j["totals"] = {{"runs", report.total_runs}, {"success", t.success}, {"failure", t.failure}, {"error", t.error},
                 {"missing", t.missing}};
  j["wall_time_s"] = report.wall_time_s ? ordered_json(*report.wall_time_s) : ordered_json(nullptr);
  j["logical_scenarios"] = ordered_json::array();
  for (const auto& g : groups_of(report)) {
    const auto gt = count(report, g.runs);
    j["logical_scenarios"].push_back({{"logical_uuid", g.logical_uuid}, {"name", g.name}, {"runs", g.runs.size()},
                                      {"success", gt.success}, {"failure", gt.failure}, {"error", gt.error},
                                      {"missing", gt.missing}});
  }
  j["runs"] = ordered_json::array();
  for (const auto& e : report.planned) {
    ordered_json r;
    r["run_id"] = e.id;
    r["logical_uuid"] = e.logical_uuid;
    r["parameter_uuid"] = e.parameter_uuid;
    const auto it = report.done.find(e.id);
    if (it == report.done.end()) {
      r["verdict"] = "missing";
      r["reason"] = "not run (batch interrupted, or its shard not merged)";
    } else {
      const ExecutionSummary& s = it->second;
      const fs::path dir = report.done_in.at(e.id);
      r["verdict"] = s.verdict;
      r["reason"] = s.reason;
      r["seed"] = s.seed ? ordered_json(*s.seed) : ordered_json(nullptr);
      r["sampled_values"] = ordered_json(s.sampled_values);
      r["attempts"] = s.attempts;
      r["sim_time"] = s.sim_time ? ordered_json(*s.sim_time) : ordered_json(nullptr);
      r["wall_time_s"] = s.wall_time_s;
      r["metrics"] = s.metrics;
      r["criteria"] = s.criteria;
      r["run_dir"] = relative_to(dir / s.run_dir, out_dir);
      r["execution_file"] = relative_to(s.file, out_dir);
    }
    j["runs"].push_back(r);
  }
  return json_text(j, 2) + "\n";
}

std::string junit_xml(const BatchReport& report) {
  pugi::xml_document doc;
  auto decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  auto suites = doc.append_child("testsuites");
  const auto t = report.totals();
  double all_time = 0;
  suites.append_attribute("name") = "orchestrator batch";
  suites.append_attribute("tests") = static_cast<unsigned long long>(report.total_runs);
  suites.append_attribute("failures") = static_cast<unsigned long long>(t.failure);
  suites.append_attribute("errors") = static_cast<unsigned long long>(t.error + t.missing);
  for (const auto& g : groups_of(report)) {
    const auto gt = count(report, g.runs);
    auto suite = suites.append_child("testsuite");
    suite.append_attribute("name") = g.name.c_str();
    suite.append_attribute("tests") = static_cast<unsigned long long>(g.runs.size());
    suite.append_attribute("failures") = static_cast<unsigned long long>(gt.failure);
    suite.append_attribute("errors") = static_cast<unsigned long long>(gt.error + gt.missing);
    auto props = suite.append_child("properties");
    auto prop = props.append_child("property");
    prop.append_attribute("name") = "logical_uuid";
    prop.append_attribute("value") = g.logical_uuid.c_str();
    double suite_time = 0;
    for (const auto* e : g.runs) {
      auto tc = suite.append_child("testcase");
      tc.append_attribute("classname") = g.name.c_str();
      const auto it = report.done.find(e->id);
      if (it == report.done.end()) {
        tc.append_attribute("name") = e->parameter_uuid.c_str();
        auto err = tc.append_child("error");
        err.append_attribute("type") = "missing";
        err.append_attribute("message") = "not run (batch interrupted, or its shard not merged)";
        continue;
      }
      const ExecutionSummary& s = it->second;
      const std::string name = s.seed ? fmt::format("{} (seed {})", e->parameter_uuid, *s.seed) : e->parameter_uuid;
      tc.append_attribute("name") = name.c_str();
      tc.append_attribute("time") = fmt::format("{:.3f}", s.wall_time_s).c_str();
      suite_time += s.wall_time_s;
      const std::string details = fmt::format("parameters: {}\nrun folder: {}\nattempts: {}\n",
                                              values_text(s.sampled_values), s.run_dir, s.attempts);
      if (s.verdict != "success") {
        auto node = tc.append_child(s.verdict == "failure" ? "failure" : "error");
        node.append_attribute("type") = s.verdict.c_str();
        node.append_attribute("message") = s.reason.c_str();
        node.append_child(pugi::node_pcdata).set_value((s.reason + "\n" + details).c_str());
      } else {
        tc.append_child("system-out").append_child(pugi::node_pcdata).set_value(details.c_str());
      }
    }
    suite.append_attribute("time") = fmt::format("{:.3f}", suite_time).c_str();
    all_time += suite_time;
  }
  suites.append_attribute("time") = fmt::format("{:.3f}", all_time).c_str();
  std::ostringstream out;
  doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  // pugixml copies bytes through: a reason quoting bad input bytes must not make the XML invalid.
  return valid_utf8(out.str());
}

std::string summary_table(const BatchReport& report) {
  const auto t = report.totals();
  std::string out = fmt::format("{} runs: {} success, {} failure, {} error, {} missing", report.total_runs, t.success,
                                t.failure, t.error, t.missing);
  if (!report.shards.empty()) {
    std::string shards;
    for (const auto& s : report.shards) shards += (shards.empty() ? "" : ", ") + s;
    out += fmt::format(" (shards {})", shards);
  }
  if (report.wall_time_s) out += fmt::format(" in {:.1f} s", *report.wall_time_s);
  out += "\n\n";
  const auto groups = groups_of(report);
  std::size_t width = std::string("logical scenario").size();
  for (const auto& g : groups) width = std::max(width, std::min<std::size_t>(g.name.size(), 48));
  out += fmt::format("{:<{}}  {:>5} {:>8} {:>8} {:>6} {:>8}\n", "logical scenario", width, "runs", "success", "failure",
                     "error", "missing");
  for (const auto& g : groups) {
    const auto gt = count(report, g.runs);
    out += fmt::format("{:<{}}  {:>5} {:>8} {:>8} {:>6} {:>8}\n", truncated(g.name, 48), width, g.runs.size(),
                       gt.success, gt.failure, gt.error, gt.missing);
  }
  std::vector<const ExecutionSummary*> bad;
  for (const auto& e : report.planned)
    if (const auto it = report.done.find(e.id); it != report.done.end() && it->second.verdict != "success")
      bad.push_back(&it->second);
  if (bad.empty()) return out;
  out += fmt::format("\nfailures and errors ({}):\n", bad.size());
  for (const auto* s : bad) {
    out += fmt::format("  {:<7}  {}  seed {}  {}\n", s->verdict, truncated(s->name.empty() ? s->logical_uuid : s->name, 40),
                       s->seed ? std::to_string(*s->seed) : "-", s->run_dir);
    out += fmt::format("           values: {}\n", values_text(s->sampled_values));
    out += fmt::format("           reason: {}\n", truncated(s->reason, 160));
  }
  return out;
}

std::string write_reports(const BatchReport& report, const fs::path& out_dir) {
  fs::create_directories(out_dir);
  write_file_atomically(out_dir / "summary.json", summary_json(report, out_dir));
  write_file_atomically(out_dir / "junit.xml", junit_xml(report));
  write_file_atomically(out_dir / "metrics.csv", batch_metrics_csv(report));
  const std::string table = summary_table(report);
  write_file_atomically(out_dir / "summary.txt", table);
  return table;
}

int batch_exit_code(const BatchReport::Totals& t) {
  if (t.error > 0 || t.missing > 0) return 2;
  if (t.failure > 0) return 1;
  return 0;
}

}  // namespace orch::batch
