#include "report/run_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <map>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "report/html_page.hpp"
#include "report/net_shapes.hpp"

namespace orch::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Distinct, readable on a light map; the ego is always the first (blue).
constexpr const char* kPalette[] = {"#1f6fd1", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                    "#17becf", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22"};

json number_or_null(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

// The columns of `table`'s rows selected by `rows`, as arrays by column name.
json columns_of(const CsvTable& table, const std::vector<std::size_t>& rows, const std::vector<std::string>& names) {
  json out = json::object();
  for (const auto& name : names) {
    const auto c = table.column(name);
    json values = json::array();
    for (const std::size_t r : rows) values.push_back(c ? number_or_null(table.number(r, *c)) : json(nullptr));
    out[name] = std::move(values);
  }
  return out;
}

// An actor id of a trace row: a number for scenario runs, the entity's name for OpenSCENARIO
// runs (docs/openscenario.md). As JSON, numbers sort before names and among themselves by value.
json actor_key(const CsvTable& table, std::size_t row, std::size_t column) {
  const std::string& cell = table.cell(row, column);
  long long number = 0;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), number);
  if (error == std::errc() && end == cell.data() + cell.size()) return number;
  return cell;
}

// Row indices per actor id, in file order (time order).
std::map<json, std::vector<std::size_t>> rows_by_actor(const CsvTable& table) {
  std::map<json, std::vector<std::size_t>> out;
  const std::size_t id = *table.column("actor_id");
  for (std::size_t r = 0; r < table.rows(); ++r) out[actor_key(table, r, id)].push_back(r);
  return out;
}

// result.json's record of the actor: by actor_id for a numeric id, by sumo_id (the entity's
// name) for a named one.
json actor_info(const json& result, const json& id) {
  const char* field = id.is_string() ? "sumo_id" : "actor_id";
  if (result.contains("actors") && result["actors"].is_array())
    for (const auto& a : result["actors"])
      if (a.is_object() && a.contains(field) && a[field] == id) return a;
  return json::object();
}

json actors_json(const RunFiles& run, std::optional<Bounds>& bounds) {
  json actors = json::array();
  if (!run.trace) return actors;
  const auto by_actor = rows_by_actor(*run.trace);
  std::size_t colour = 1;
  for (const auto& [id, rows] : by_actor) {
    const json info = actor_info(run.result, id);
    const bool ego = info.value("ego", id == 0 && !info.contains("ego"));
    json a = columns_of(*run.trace, rows, {"time", "x", "y", "heading", "speed", "accel", "lat_offset", "scene_id"});
    a["actor_id"] = id;
    a["ego"] = ego;
    a["description"] = info.value("description", "");
    a["model_id"] = info.value("model_id", "");
    // A result.json from before actors were recorded: a typical car's size, said so.
    a["size_known"] = info.contains("length");
    a["length"] = info.value("length", 4.5);
    a["width"] = info.value("width", 1.8);
    const std::string given = info.value("color", "");
    a["color"] = ego ? std::string(kPalette[0]) : !given.empty() ? "#" + given : std::string(kPalette[colour++ % 10]);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double x = a["x"][i].is_number() ? a["x"][i].get<double>() : 0.0;
      const double y = a["y"][i].is_number() ? a["y"][i].get<double>() : 0.0;
      if (!bounds) bounds = Bounds{x, y, x, y};
      bounds = Bounds{std::min(bounds->min_x, x), std::min(bounds->min_y, y), std::max(bounds->max_x, x),
                      std::max(bounds->max_y, y)};
    }
    actors.push_back(std::move(a));
  }
  // The ego first: it is drawn on top and leads the legend.
  std::stable_sort(actors.begin(), actors.end(), [](const json& l, const json& r) {
    return l["ego"].get<bool>() && !r["ego"].get<bool>();
  });
  return actors;
}

// Background vehicles near the actors (--trace-background), or an OpenSCENARIO run's
// TrafficAction vehicles (traffic_actions.csv, with `extra` columns), thinned to at most
// ~15,000 rows so a long dense run stays a file a browser opens at once.
json vehicles_json(const CsvTable& table, const std::vector<std::string>& extra = {}) {
  constexpr std::size_t kMaxRows = 15000;
  const std::size_t time = *table.column("time");
  std::vector<double> times;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const double t = table.number(r, time).value_or(0);
    if (times.empty() || times.back() != t) times.push_back(t);
  }
  const std::size_t stride = std::max<std::size_t>(1, (table.rows() + kMaxRows - 1) / kMaxRows);
  std::vector<std::size_t> rows;
  std::size_t step_index = 0;
  double last = table.rows() ? table.number(0, time).value_or(0) : 0;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const double t = table.number(r, time).value_or(0);
    if (t != last) {
      ++step_index;
      last = t;
    }
    if (step_index % stride == 0) rows.push_back(r);
  }
  std::vector<std::string> columns{"time", "x", "y", "heading", "length", "width"};
  columns.insert(columns.end(), extra.begin(), extra.end());
  json out = columns_of(table, rows, columns);
  json ids = json::array();
  const std::size_t id = *table.column("vehicle_id");
  for (const std::size_t r : rows) ids.push_back(table.cell(r, id));
  out["vehicle_id"] = std::move(ids);
  out["stride_steps"] = stride;
  return out;
}

void widen(std::optional<Bounds>& bounds, const CsvTable& table) {
  const std::size_t xc = *table.column("x"), yc = *table.column("y");
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const auto x = table.number(r, xc), y = table.number(r, yc);
    if (!x || !y) continue;
    bounds = Bounds{std::min(bounds->min_x, *x), std::min(bounds->min_y, *y), std::max(bounds->max_x, *x),
                    std::max(bounds->max_y, *y)};
  }
}

json metrics_json(const CsvTable& table) {
  json out = json::object();
  for (const auto& [id, rows] : rows_by_actor(table)) {
    std::vector<std::string> names;
    for (const auto& c : table.columns())
      if (c != "actor_id" && c != "leader" && c != "min_dist_to") names.push_back(c);
    out[id.is_string() ? id.get<std::string>() : id.dump()] = columns_of(table, rows, names);
  }
  return out;
}

json lanes_json(const json& result, const fs::path& run_dir, const std::optional<Bounds>& bounds, json& problems) {
  json lanes = json::array();
  if (!bounds) return lanes;  // nothing was traced: nothing to place on a map
  const std::string net = result.contains("inputs") && result["inputs"].contains("net")
                              ? result["inputs"]["net"].value("path", "")
                              : "";
  if (net.empty()) return lanes;
  fs::path file = net;
  if (file.is_relative() && !fs::exists(file)) file = run_dir / file;
  try {
    constexpr double kMargin = 60;  // m of road around the trajectories
    const Bounds near{bounds->min_x - kMargin, bounds->min_y - kMargin, bounds->max_x + kMargin,
                      bounds->max_y + kMargin};
    for (const auto& l : read_lane_shapes(file, near))
      lanes.push_back({{"id", l.id}, {"width", l.width}, {"internal", l.internal}, {"xy", l.xy}});
  } catch (const OrchError& e) {
    problems.push_back(fmt::format("the map is not drawn: {}", e.what()));
  }
  return lanes;
}

}  // namespace

json run_report_data(const RunFiles& run, const std::vector<std::string>& read_problems) {
  json data;
  data["kind"] = "run";
  data["orchestrator_version"] = ORCH_VERSION;
  data["result"] = run.result;
  data["problems"] = read_problems;
  std::optional<Bounds> bounds;
  data["actors"] = actors_json(run, bounds);
  // The map reaches the TrafficAction vehicles too (a swarm spreads hundreds of m around the ego).
  if (bounds && run.traffic_actions) widen(bounds, *run.traffic_actions);
  data["lanes"] = lanes_json(run.result, run.dir, bounds, data["problems"]);
  data["background"] = run.background ? vehicles_json(*run.background) : json(nullptr);
  data["traffic_actions"] = run.traffic_actions ? vehicles_json(*run.traffic_actions, {"traffic"}) : json(nullptr);
  data["metrics"] = run.metrics ? metrics_json(*run.metrics) : json(nullptr);
  data["log"] = run.run_log;
  return data;
}

fs::path write_run_report(const fs::path& dir) {
  std::vector<std::string> problems;
  const RunFiles run = read_run_files(dir, &problems);
  const json data = run_report_data(run, problems);
  const std::string title = run.result.value("title", "");
  const std::string page = html_page(fmt::format("{} — {}", title.empty() ? "run" : title, run.result.value("verdict", "?")),
                                     run_report_script(), data);
  const fs::path out = dir / "report.html";
  write_file_atomically(out, page);
  return out;
}

}  // namespace orch::report
