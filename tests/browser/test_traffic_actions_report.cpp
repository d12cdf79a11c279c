// The run report of an OpenSCENARIO run with TrafficActions (tests/data/openscenario/
// traffic_actions.xosc: a swarm, a source, a sink) opened in headless Chromium: the header
// says what the traffic did as result.json does, not "none"; the table lists each action; the
// replay draws the TrafficAction vehicles at traffic_actions.csv's positions.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "browser/webdriver.hpp"
#include "results/run_files.hpp"
#include "support/cli_runner.hpp"

namespace fs = std::filesystem;
using namespace orch::test;

namespace {

using TrafficActionsReportInBrowser = BrowserTest;

// The centre of a box drawn as an SVG polygon "x,y x,y x,y x,y".
std::pair<double, double> centre_of(const std::string& points) {
  std::stringstream ss(points);
  std::string pair;
  double x = 0, y = 0;
  int n = 0;
  while (ss >> pair) {
    const auto c = pair.find(',');
    x += std::stod(pair.substr(0, c));
    y += std::stod(pair.substr(c + 1));
    ++n;
  }
  if (n != 4) throw std::runtime_error("not a box: " + points);
  return {x / 4, y / 4};
}

}  // namespace

TEST_F(TrafficActionsReportInBrowser, TheHeaderCountsTheTrafficAndTheReplayDrawsItsVehicles) {
  TempDir dir;
  const fs::path out = dir / "run";
  const auto r = run_cli({"run", std::string(ORCH_SOURCE_DIR) + "/tests/data/openscenario/traffic_actions.xosc", "--out",
                          out.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const orch::RunFiles run = orch::read_run_files(out);
  ASSERT_TRUE(run.traffic_actions.has_value());
  const auto& traffic = run.result["storyboard_traffic"];
  Browser& b = *browser_;
  b.open(out / "report.html");
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});

  // The header: the kinds and result.json's counts.
  const std::string meta = b.eval("return document.querySelector('.meta').innerText;");
  const std::string expected = "TRAFFIC\nswarm + source + sink (" + std::to_string(traffic["spawned"].get<int>()) +
                               " spawned, " + std::to_string(traffic["removed"].get<int>()) + " removed)";
  EXPECT_NE(meta.find(expected), std::string::npos) << meta;
  // One row per action, with its spawned count.
  const auto rows = b.eval(
      "return [...document.querySelectorAll('#traffic-actions tr[data-traffic]')]"
      ".map(r => [...r.children].map(td => td.textContent));");
  ASSERT_EQ(rows.size(), 3u) << rows.dump();
  EXPECT_EQ(rows[0][0], "Crowd");
  EXPECT_EQ(rows[0][4], std::to_string(traffic["actions"][0]["spawned"].get<int>()));
  EXPECT_EQ(rows[1][3], "20.00");  // the source's TrafficStopAction
  EXPECT_EQ(rows[2][1], "sink");

  // The replay at a few times: a box per vehicle in traffic_actions.csv at that step, where the file has it.
  const auto& t = *run.traffic_actions;
  const auto c = [&](const char* name) { return *t.column(name); };
  std::map<double, std::map<std::string, std::pair<double, double>>> at;
  for (std::size_t row = 0; row < t.rows(); ++row)
    at[*t.number(row, c("time"))][t.cell(row, c("vehicle_id"))] = {*t.number(row, c("x")), *t.number(row, c("y"))};
  int checked = 0;
  for (double time : {5.0, 15.0, 30.0}) {
    const auto step = at.find(time);
    ASSERT_NE(step, at.end()) << time;
    b.eval("window.orchReport.setTime(arguments[0]);", {time});
    const auto drawn = b.eval(
        "return [...document.querySelectorAll('#map-replay polygon.traffic-box')]"
        ".filter(p => p.getAttribute('visibility') === 'visible').map(p => [p.dataset.vehicle, p.getAttribute('points')]);");
    ASSERT_EQ(drawn.size(), step->second.size()) << "t=" << time << " " << drawn.dump();
    for (const auto& d : drawn) {
      const std::string id = d[0];
      ASSERT_TRUE(step->second.count(id)) << id;
      const auto [x, y] = centre_of(d[1]);
      EXPECT_NEAR(x, step->second.at(id).first, 2e-3) << id;
      EXPECT_NEAR(y, step->second.at(id).second, 2e-3) << id;
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
  b.resize(1400, 1500);
  b.eval("window.orchReport.setTime(15);");
  fs::create_directories(ORCH_SCREENSHOT_DIR);
  std::ofstream(fs::path(ORCH_SCREENSHOT_DIR) / "report_traffic_actions.png", std::ios::binary) << b.screenshot();
  EXPECT_EQ(b.console_errors(), std::vector<std::string>{});
}
