// The run report opened in headless Chromium: it loads without console errors, draws one
// trajectory per actor, its replay puts the ego's box where the trace says, metrics and
// criteria appear when the run has them, and a run that could not run still shows why.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "browser/webdriver.hpp"
#include "results/run_files.hpp"
#include "run/metrics_recorder.hpp"
#include "support/cli_runner.hpp"

namespace fs = std::filesystem;
using namespace orch::test;

namespace {

// One run of the highway cut-in, shared by the tests of this file (it takes a few seconds).
const fs::path& highway_run() {
  static const fs::path dir = [] {
    static TempDir root;
    const fs::path out = root / "highway";
    const auto r = run_cli({"run", std::string(ORCH_SOURCE_DIR) + "/scenarios/highway_cut_in.json", "--out",
                            out.string(), "-q", "--trace-background", "--traffic", "light"});
    if (r.exit_code != 0) throw std::runtime_error(r.output);
    if (r.output.find("report: file://" + fs::absolute(out / "report.html").string() + " (") == std::string::npos)
      throw std::runtime_error("run did not print the report's path: " + r.output);
    return out;
  }();
  return dir;
}

void save_screenshot(Browser& b, const std::string& name) {
  fs::create_directories(ORCH_SCREENSHOT_DIR);
  std::ofstream(fs::path(ORCH_SCREENSHOT_DIR) / name, std::ios::binary) << b.screenshot();
}

// The centre and heading of a box drawn as an SVG polygon "x,y x,y x,y x,y" (front-left,
// front-right, rear-right, rear-left), read back from the page.
struct Box {
  double x, y, heading, length, width;
};
Box box_from_points(const std::string& points) {
  std::vector<std::pair<double, double>> p;
  std::stringstream ss(points);
  std::string pair;
  while (ss >> pair) {
    const auto c = pair.find(',');
    p.emplace_back(std::stod(pair.substr(0, c)), std::stod(pair.substr(c + 1)));
  }
  if (p.size() != 4) throw std::runtime_error("not a box: " + points);
  Box b{};
  for (const auto& [x, y] : p) {
    b.x += x / 4;
    b.y += y / 4;
  }
  b.heading = std::atan2(p[0].second - p[3].second, p[0].first - p[3].first);
  b.length = std::hypot(p[0].first - p[3].first, p[0].second - p[3].second);
  b.width = std::hypot(p[0].first - p[1].first, p[0].second - p[1].second);
  return b;
}

using RunReportInBrowser = BrowserTest;

}  // namespace

TEST_F(RunReportInBrowser, LoadsWithoutConsoleErrorsAndDrawsOneTrajectoryPerActor) {
  Browser& b = *browser_;
  b.open(highway_run() / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  const orch::RunFiles run = orch::read_run_files(highway_run());
  std::set<std::string> actors;
  const auto id = *run.trace->column("actor_id");
  for (std::size_t r = 0; r < run.trace->rows(); ++r) actors.insert(run.trace->cell(r, id));
  ASSERT_EQ(actors.size(), 2u);
  const auto drawn = b.eval(
      "return [...document.querySelectorAll('#map-overview polyline.trajectory')]"
      ".map(p => [p.dataset.actor, p.getAttribute('points').split(' ').length]);");
  ASSERT_EQ(drawn.size(), actors.size()) << drawn.dump();
  for (const auto& d : drawn) {
    EXPECT_TRUE(actors.count(d[0].get<std::string>())) << d.dump();
    EXPECT_GT(d[1].get<int>(), 1000) << "a trajectory of a 70 s run at 0.05 s has a point per step";
  }
  // The map under them: lanes of the net around the trajectories.
  EXPECT_GT(b.eval("return document.querySelectorAll('#map-overview polyline.lane').length;").get<int>(), 5);
  // The header tells the verdict and the reason as result.json does.
  EXPECT_EQ(b.eval("return document.querySelector('.verdict').textContent;"), run.result["verdict"]);
  EXPECT_NE(b.eval("return document.body.innerText;").get<std::string>().find(run.result["reason"].get<std::string>()),
            std::string::npos);
  // The scene timeline's markers show their run-log line on hover: every transition's line.
  const auto marks = b.eval(
      "const c = Chart.getChart(document.getElementById('chart-timeline'));"
      "return c.data.datasets.find(d => d.label === 'scene').data.map(p => p.text);");
  const std::string log = slurp(highway_run() / "run.log");
  ASSERT_EQ(marks.size(), run.result["scenes"].size()) << marks.dump();
  for (const auto& m : marks) {
    EXPECT_NE(log.find(m.get<std::string>() + "\n"), std::string::npos) << m;
    EXPECT_EQ(m.get<std::string>().rfind("t=", 0), 0u) << m;
  }
  b.resize(1400, 1900);
  b.eval("window.orchReport.setTime(20);");
  save_screenshot(b, "run_report.png");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
}

TEST_F(RunReportInBrowser, TheReplaySliderMovesTheEgosBoxToTheTracesPositionAtThatTime) {
  Browser& b = *browser_;
  b.open(highway_run() / "report.html");
  const orch::RunFiles run = orch::read_run_files(highway_run());
  const auto& t = *run.trace;
  const auto c = [&](const char* name) { return *t.column(name); };
  double ego_length = 0, ego_width = 0;
  for (const auto& a : run.result["actors"])
    if (a["ego"].get<bool>()) {
      ego_length = a["length"].get<double>();
      ego_width = a["width"].get<double>();
    }
  ASSERT_GT(ego_length, 0);
  int checked = 0;
  for (std::size_t r = 0; r < t.rows(); r += 173) {
    if (t.cell(r, c("actor_id")) != "0") continue;
    const double time = *t.number(r, c("time"));
    // As a person drags it: the slider's value changes and it fires "input".
    b.eval("const s = document.getElementById('time-slider'); s.value = arguments[0];"
           "s.dispatchEvent(new Event('input', {bubbles: true}));",
           {time});
    const std::string points =
        b.eval("return document.querySelector('#map-replay polygon.actor-box[data-actor=\"0\"]').getAttribute('points');");
    const Box box = box_from_points(points);
    EXPECT_NEAR(box.x, *t.number(r, c("x")), 2e-3) << "t=" << time;
    EXPECT_NEAR(box.y, *t.number(r, c("y")), 2e-3) << "t=" << time;
    EXPECT_NEAR(std::remainder(box.heading - *t.number(r, c("heading")), 2 * M_PI), 0, 1e-3) << "t=" << time;
    EXPECT_NEAR(box.length, ego_length, 2e-3);
    EXPECT_NEAR(box.width, ego_width, 2e-3);
    // The readout under the replay shows the same row.
    EXPECT_EQ(b.eval("return document.querySelector('#replay-readout tr[data-actor=\"0\"] td.x').textContent;"),
              t.cell(r, c("x")));
    ++checked;
  }
  EXPECT_GT(checked, 5);
  // The background vehicles traced (--trace-background) are drawn at their step's positions.
  ASSERT_TRUE(run.background.has_value());
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
}

TEST_F(RunReportInBrowser, MetricsAndCriteriaOfTheEvaluationAppearWhenTheRunHasThem) {
  // A copy of the run with a metrics.csv and criteria in the evaluation's shape.
  TempDir copy;
  const fs::path dir = copy / "run";
  fs::copy(highway_run(), dir);
  std::ofstream metrics(dir / "metrics.csv");
  metrics << orch::metrics::MetricsRecorder::header() << "\n";
  // Empty cells for the columns after the first 14 (metrics added later).
  const std::string later(orch::metrics_columns().size() - 14, ',');
  int rows = 0;
  for (int i = 0; i <= 400; ++i, ++rows) {
    const double time = 0.05 * (i + 1);
    // TTC exists only while closing in: empty cells elsewhere.
    const std::string ttc = i % 2 ? fmt::format("{:.3f}", 3.0 + i * 0.01) : "";
    metrics << fmt::format("{:.3f},0,1,{:.3f},{:.3f},{},{:.3f},,0.1,0.0,0.0,0,{:.3f},1{}\n", time, 30.0 - i * 0.02, -1.5,
                           ttc, 1.2, 25.0, later);
  }
  metrics.close();
  nlohmann::json result = read_json(dir / "result.json");
  result["criteria"] = {{{"name", "keeps a 1 s headway"}, {"actor", 0}, {"metric", "thw"}, {"expected", ">= 1.5"},
                         {"actual", 1.2}, {"at_time", 12.5}, {"success", false}},
                        {{"name", "no collision"}, {"actor", 0}, {"metric", "collisions"}, {"expected", "0"},
                         {"actual", 0}, {"at_time", nullptr}, {"success", true}}};
  std::ofstream(dir / "result.json") << result.dump(2);
  const auto r = run_cli({"report", dir.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;

  Browser& b = *browser_;
  b.open(dir / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  const auto points = b.eval(
      "return ['chart-gap', 'chart-ttc'].map(id => { const c = Chart.getChart(document.getElementById(id));"
      " return c ? c.data.datasets.map(d => [d.label, d.data.length, d.data.filter(p => p.y !== null).length]) : null; });");
  ASSERT_FALSE(points[0].is_null()) << "no gap chart";
  ASSERT_FALSE(points[1].is_null()) << "no TTC chart";
  EXPECT_EQ(points[0][0], nlohmann::json({"gap", rows, rows}));
  EXPECT_EQ(points[1][0], nlohmann::json({"TTC", rows, rows / 2}));  // the empty cells stay gaps
  EXPECT_EQ(points[1][1], nlohmann::json({"THW", rows, rows}));
  const std::string failing = b.eval("return document.querySelector('.card table.criteria').innerText;");
  EXPECT_NE(failing.find("keeps a 1 s headway"), std::string::npos) << failing;
  EXPECT_EQ(failing.find("no collision"), std::string::npos) << "only failing criteria in the header: " << failing;

  // Without metrics.csv (a run written before the evaluation existed), the same report has
  // no metric charts.
  const fs::path bare = copy / "bare";
  fs::copy(highway_run(), bare);
  fs::remove(bare / "metrics.csv");
  fs::remove(bare / "report.html");
  ASSERT_EQ(run_cli({"report", bare.string()}).exit_code, 0);
  b.open(bare / "report.html");
  EXPECT_TRUE(b.eval("return document.getElementById('chart-gap') === null;").get<bool>());
}

TEST_F(RunReportInBrowser, TheReportOfARunThatCouldNotRunOpensAndShowsTheError) {
  TempDir dir;
  const fs::path scenario = dir.write("bad_map.json", R"({
  "title": "No such map", "map_id": "no_such_map",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}, "others": []},
  "scenario": {"opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 5}}, "next_scenes": [1]},
               "scenes": [], "ending_scenes": [{"scene_id": 1, "description": "end",
               "conditions": {"and": [{"simulation_time": {"comparison": ">=", "value": 1}}]}}]}
})");
  const fs::path out = dir / "out";
  const auto r = run_cli({"run", scenario.string(), "--out", out.string(), "-q"});
  ASSERT_EQ(r.exit_code, 2) << r.output;
  ASSERT_TRUE(fs::exists(out / "report.html")) << r.output;
  const std::string reason = read_json(out / "result.json")["reason"];

  Browser& b = *browser_;
  b.open(out / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  EXPECT_EQ(b.eval("return document.querySelector('.verdict').textContent;"), "error");
  EXPECT_EQ(b.eval("return document.getElementById('run-error').textContent;"), reason);
  EXPECT_NE(reason.find("no_such_map"), std::string::npos) << reason;
  EXPECT_NE(b.eval("return document.body.innerText;").get<std::string>().find("No trace"), std::string::npos);
}

TEST_F(RunReportInBrowser, AnOpenScenarioRunShowsItsEntitiesByNameWithTheEgoFirst) {
  TempDir dir;
  const fs::path out = dir / "osc";
  const auto r = run_cli({"run", std::string(ORCH_SOURCE_DIR) + "/scenarios/openscenario/cut_in_traffic.xosc", "--out",
                          out.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Browser& b = *browser_;
  b.open(out / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  const auto drawn = b.eval(
      "return [...document.querySelectorAll('#map-overview polyline.trajectory')].map(p => p.dataset.actor).sort();");
  EXPECT_EQ(drawn, nlohmann::json({"CutIn", "Ego"}));
  // The speed chart has a line per entity, the ego's (the ALKSController one) first, with who
  // drove it and why.
  const auto labels = b.eval(
      "return Chart.getChart(document.getElementById('chart-speed')).data.datasets.map(d => d.label);");
  EXPECT_EQ(labels, nlohmann::json({"ego Ego — driven by SUMO (controller ALKSController is a system under test)",
                                    "CutIn"}));
  // The replay puts the ego's box where the trace has it.
  const orch::RunFiles run = orch::read_run_files(out);
  const auto& t = *run.trace;
  const auto c = [&](const char* name) { return *t.column(name); };
  std::size_t row = t.rows() / 2;
  while (t.cell(row, c("actor_id")) != "Ego") ++row;
  b.eval("window.orchReport.setTime(arguments[0]);", {*t.number(row, c("time"))});
  const std::string points =
      b.eval("return document.querySelector('#map-replay polygon.actor-box[data-actor=\"Ego\"]').getAttribute('points');");
  const Box box = box_from_points(points);
  EXPECT_NEAR(box.x, *t.number(row, c("x")), 2e-3);
  EXPECT_NEAR(box.y, *t.number(row, c("y")), 2e-3);
  // The storyboard timeline: Acts and Events at their times, each with its run-log line.
  const auto marks = b.eval(
      "const c = Chart.getChart(document.getElementById('chart-timeline'));"
      "return Object.fromEntries(c.data.datasets.map(d => [d.label, d.data.map(p => [p.x, p.text])]));");
  const std::string log = slurp(out / "run.log");
  for (const char* row_name : {"act", "event", "action"}) {
    ASSERT_TRUE(marks.contains(row_name)) << marks.dump();
    EXPECT_FALSE(marks[row_name].empty()) << row_name;
    for (const auto& m : marks[row_name]) EXPECT_NE(log.find(m[1].get<std::string>() + "\n"), std::string::npos) << m;
  }
  bool act_start = false, cut_in_event = false;
  for (const auto& m : marks["act"]) act_start |= m[1].get<std::string>().ends_with("act CutInAct startTransition");
  for (const auto& m : marks["event"])
    cut_in_event |= m[1].get<std::string>().ends_with("event CutInEvent startTransition") && m[0].get<double>() > 1;
  EXPECT_TRUE(act_start && cut_in_event) << marks.dump();
  // The header says how the storyboard ended, not "ending scene".
  const std::string text = b.eval("return document.querySelector('.meta').innerText;");
  EXPECT_EQ(text.find("ending scene"), std::string::npos) << text;
  EXPECT_NE(text.find("StopTrigger at 27.60 s; last: "), std::string::npos) << text;
  // ... and who drove the ego (result.json's ego_model).
  const std::string ego_model = nlohmann::json::parse(slurp(out / "result.json"))["ego_model"].get<std::string>();
  EXPECT_NE(text.find("EGO DRIVEN BY\n" + ego_model + "\n"), std::string::npos) << text;
  // The ego's gap and TTC from metrics.csv.
  EXPECT_EQ(b.eval("return !!document.getElementById('chart-ttc');"), true);
  b.resize(1400, 2300);  // down to the storyboard timeline
  save_screenshot(b, "report_openscenario.png");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
}

TEST(RunReport, NoReportSkipsIt) {
  TempDir dir;
  const auto r = run_cli({"run", std::string(ORCH_SOURCE_DIR) + "/scenarios/alks_obstacle_stop.json", "--out",
                          (dir / "out").string(), "-q", "--no-report"});
  ASSERT_LE(r.exit_code, 1) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "result.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "report.html"));
  EXPECT_EQ(r.output.find("report:"), std::string::npos) << r.output;
}
