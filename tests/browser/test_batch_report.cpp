// The batch report opened in headless Chromium: counts, one scatter point per run in its
// verdict's colour, the scene graph with the runs that took each transition, links to the
// runs' own reports; after `batch merge` too.
#include <gtest/gtest.h>

#include <set>

#include <fstream>
#include <map>

#include "browser/webdriver.hpp"
#include "e2e/test_batch_support.hpp"

namespace fs = std::filesystem;
using namespace orch::test;
using namespace orch::test::batch;

namespace {

const std::map<std::string, std::string> kVerdictColors = {
    {"success", "#2e9d46"}, {"failure", "#d62f2f"}, {"error", "#8a4fd0"}};

// Seeds 100.. in order: success, failure, error, success, failure, success.
std::vector<QuickSet> sets() {
  return {{"s0", 0.5, 5}, {"s1", 2.0, 5}, {"s2", 0.5, 999999}, {"s3", 0.6, 5}, {"s4", 1.5, 5}, {"s5", 0.7, 5}};
}

// seed -> the run in summary.json (what the scatter must show).
std::map<long long, nlohmann::json> runs_by_seed(const fs::path& summary) {
  std::map<long long, nlohmann::json> out;
  const nlohmann::json j = read_json(summary);
  for (const auto& r : j["runs"]) out[r["seed"].get<long long>()] = r;
  return out;
}

void expect_scatter_matches(Browser& b, const fs::path& batch_dir) {
  const auto expected = runs_by_seed(batch_dir / "summary.json");
  ASSERT_EQ(expected.size(), sets().size());
  // Colour by verdict, then read every point of the first scatter plot back from its chart.
  const auto points = b.eval(
      "const sel = document.querySelector('select.color-by'); if (sel) { sel.value = ''; sel.dispatchEvent(new Event('change')); }"
      "const c = Chart.getChart(document.querySelector('canvas.scatter'));"
      "return [c.canvas.dataset.x, c.canvas.dataset.y, c.data.datasets.flatMap(d => d.data.map(p => "
      "({seed: p.run.seed, x: p.x, y: p.y, label: d.label, color: d.backgroundColor})))];");
  // The parameters that vary (q.start only for the run that cannot start) are the axes.
  ASSERT_EQ(points[0], "q.end");
  ASSERT_EQ(points[1], "q.start");
  ASSERT_EQ(points[2].size(), expected.size()) << points.dump();
  std::map<long long, int> seen;
  for (const auto& p : points[2]) {
    const long long seed = p["seed"];
    ++seen[seed];
    ASSERT_TRUE(expected.count(seed)) << p.dump();
    const auto& run = expected.at(seed);
    EXPECT_EQ(p["label"], run["verdict"]) << p.dump();
    EXPECT_EQ(p["color"], kVerdictColors.at(run["verdict"])) << p.dump();
    EXPECT_EQ(p["x"], run["sampled_values"]["q"]["end"]) << p.dump();
    EXPECT_EQ(p["y"], run["sampled_values"]["q"]["start"]) << p.dump();
  }
  for (const auto& [seed, n] : seen) EXPECT_EQ(n, 1) << "seed " << seed;
}

using BatchReportInBrowser = BrowserTest;

}  // namespace

TEST_F(BatchReportInBrowser, OnePointPerRunInItsVerdictsColourAndTheSceneGraphCountsTheRuns) {
  TempDir in, out_root;
  const auto logical = write_quick_batch(in, sets());
  const fs::path out = out_root / "b";
  const auto r = run_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "2", "--retries", "0"});
  ASSERT_EQ(r.exit_code, 2) << r.output;
  ASSERT_NE(r.output.find("report: file://" + fs::absolute(out / "report.html").string()), std::string::npos) << r.output;

  Browser& b = *browser_;
  b.open(out / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  EXPECT_EQ(b.eval("return [...document.querySelectorAll('#counts .count b')].map(e => e.textContent);"),
            nlohmann::json({"3", "2", "1", "0"}));
  expect_scatter_matches(b, out);
  fs::create_directories(ORCH_SCREENSHOT_DIR);
  std::ofstream(fs::path(ORCH_SCREENSHOT_DIR) / "batch_report.png", std::ios::binary) << b.screenshot();

  // Scene graph: 0 -> 1; every run that started took it except the one that could not run.
  const auto edges = b.eval("return [...document.querySelectorAll('svg.graph path.edge')].map(e => Number(e.dataset.runs));");
  EXPECT_EQ(edges, nlohmann::json({3})) << "only the successes reach ending scene 1";
  // The table lists every run, filterable by verdict, each linking its own report.
  EXPECT_EQ(b.eval("return document.querySelectorAll('#runs tbody tr').length;"), 6);
  b.eval("const s = document.getElementById('verdict-filter'); s.value = 'failure'; s.dispatchEvent(new Event('change'));");
  EXPECT_EQ(b.eval("return document.querySelectorAll('#runs tbody tr').length;"), 2);
  const auto links = b.eval("return [...document.querySelectorAll('#runs tbody a')].map(a => a.getAttribute('href'));");
  ASSERT_EQ(links.size(), 2u);
  for (const auto& l : links) EXPECT_TRUE(fs::exists(out / l.get<std::string>())) << l;

  // A run's link opens its report.
  b.open(out / links[0].get<std::string>());
  EXPECT_EQ(b.eval("return document.querySelector('.verdict').textContent;"), "failure");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
}

TEST_F(BatchReportInBrowser, AMergeOfShardsGetsTheSameReport) {
  TempDir in, out_root;
  const auto logical = write_quick_batch(in, sets());
  for (const char* shard : {"1/2", "2/2"}) {
    const auto r = run_cli({"batch", logical.string(), "--out", (out_root / (std::string("shard") + shard[0])).string(),
                            "--shard", shard, "--jobs", "2", "--retries", "0"});
    ASSERT_LE(r.exit_code, 2) << r.output;
  }
  const fs::path merged = out_root / "merged";
  const auto r = run_cli({"batch", "merge", (out_root / "shard1").string(), (out_root / "shard2").string(), "--out",
                          merged.string()});
  ASSERT_EQ(r.exit_code, 2) << r.output;
  ASSERT_TRUE(fs::exists(merged / "report.html")) << r.output;

  Browser& b = *browser_;
  b.open(merged / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  expect_scatter_matches(b, merged);
  // Links lead into the shard folders, where the runs are.
  const auto links = b.eval("return [...document.querySelectorAll('#runs tbody a')].map(a => a.getAttribute('href'));");
  EXPECT_EQ(links.size(), 6u) << "every run has a report, the one that could not run too: " << links.dump();
  for (const auto& l : links) EXPECT_TRUE(fs::exists(merged / l.get<std::string>())) << l;
}

TEST_F(BatchReportInBrowser, WithMetricsThePointsTakeTheColourOfAChosenMetricAndItsHistogramIsDrawn) {
  TempDir in, out_root;
  const auto logical = write_quick_batch(in, sets());
  const fs::path out = out_root / "b";
  ASSERT_EQ(run_cli({"batch", logical.string(), "--out", out.string(), "--jobs", "2", "--retries", "0"}).exit_code, 2);
  // The evaluation's per-actor summary in every run's result.json: min TTC = seed - 100.
  const auto runs = runs_by_seed(out / "summary.json");
  for (const auto& [seed, run] : runs) {
    const fs::path file = out / run["run_dir"].get<std::string>() / "result.json";
    nlohmann::json result = read_json(file);
    result["metrics"] = {{"0", {{"min_ttc", static_cast<double>(seed - 100)}, {"max_decel", 1.5}}}};
    std::ofstream(file) << result.dump(2);
  }
  const auto r = run_cli({"report", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;

  Browser& b = *browser_;
  b.open(out / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
  EXPECT_EQ(b.eval("return [...document.querySelector('select.color-by').options].map(o => o.value);"),
            nlohmann::json({"", "0.max_decel", "0.min_ttc"}));
  EXPECT_EQ(b.eval("return document.querySelector('select.color-by').value;"), "0.min_ttc") << "a minimum TTC first";
  const auto colours = b.eval(
      "const c = Chart.getChart(document.querySelector('canvas.scatter')); const d = c.data.datasets[0];"
      "return d.data.map((p, i) => [p.run.seed, d.pointBackgroundColor[i], d.pointBorderColor[i]]);");
  ASSERT_EQ(colours.size(), runs.size()) << colours.dump();
  for (const auto& c : colours) {
    const long long seed = c[0];
    // Red for the smallest TTC (seed 100), blue for the largest (seed 105); verdict as border.
    if (seed == 100) {
      EXPECT_EQ(c[1], "rgb(240,110,30)");
    }
    if (seed == 105) {
      EXPECT_EQ(c[1], "rgb(40,110,220)");
    }
    EXPECT_EQ(c[2], kVerdictColors.at(runs.at(seed)["verdict"])) << c.dump();
  }
  const auto histogram = b.eval(
      "const c = Chart.getChart(document.querySelector('canvas.histogram'));"
      "return c.data.datasets.map(d => [d.label, d.data.reduce((a, b) => a + b, 0)]);");
  EXPECT_EQ(histogram, nlohmann::json::parse(R"([["success", 3], ["failure", 2], ["error", 1]])"));

  // A metric spanning only 0.005 s still gets one label per bin, not sixteen "1.98".
  for (const auto& [seed, run] : runs) {
    const fs::path file = out / run["run_dir"].get<std::string>() / "result.json";
    nlohmann::json result = read_json(file);
    result["metrics"]["0"]["min_ttc"] = 1.98 + 0.001 * static_cast<double>(seed - 100);
    std::ofstream(file) << result.dump(2);
  }
  ASSERT_EQ(run_cli({"report", out.string()}).exit_code, 0);
  b.open(out / "report.html");
  const auto labels = b.eval("return Chart.getChart(document.querySelector('canvas.histogram')).data.labels;");
  ASSERT_EQ(labels.size(), 16u) << labels.dump();
  EXPECT_EQ(std::set<std::string>(labels.begin(), labels.end()).size(), 16u) << labels.dump();

  // A minimum TTC that is the same in every run tells them not apart: the default colour is
  // a measure that varies.
  for (const auto& [seed, run] : runs) {
    const fs::path file = out / run["run_dir"].get<std::string>() / "result.json";
    nlohmann::json result = read_json(file);
    result["metrics"]["0"] = {{"min_ttc", 0.0}, {"max_decel", 1.0 + static_cast<double>(seed - 100)}};
    std::ofstream(file) << result.dump(2);
  }
  ASSERT_EQ(run_cli({"report", out.string()}).exit_code, 0);
  b.open(out / "report.html");
  EXPECT_EQ(b.eval("return document.querySelector('select.color-by').value;"), "0.max_decel");
}
