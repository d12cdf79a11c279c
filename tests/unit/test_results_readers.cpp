// Reading a run's files back (orchestrator/results) and the data the run report draws from
// them (orchestrator/report): shapes checked, bad files named with their line, optional
// files absent without harm.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>

#include <fstream>
#include <map>

#include "core/errors.hpp"
#include "report/net_shapes.hpp"
#include "report/run_report.hpp"
#include "results/run_files.hpp"
#include "run/metrics_recorder.hpp"
#include "run/trace_writer.hpp"
#include "support/cli_runner.hpp"

namespace fs = std::filesystem;
using namespace orch;

namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

// A run folder as a run writes it: result.json, trace.csv (two actors, three steps), run.log.
// A metrics.csv in the writer's columns (the metric table's): each row's cells by column name,
// the others empty, so the file keeps the writer's shape when a metric is added.
std::string metrics_csv(const std::vector<std::map<std::string, std::string>>& rows) {
  std::string text = metrics::MetricsRecorder::header() + "\n";
  for (const auto& row : rows) {
    const auto& columns = metrics_columns();
    std::string line;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c > 0) line += ',';
      if (const auto it = row.find(columns[c]); it != row.end()) line += it->second;
    }
    text += line + "\n";
  }
  return text;
}

void write_run(const test::TempDir& dir, const std::string& net_path) {
  nlohmann::json result = {{"verdict", "failure"}, {"reason", "stop"}, {"sim_time", 0.15}, {"step", 0.05},
                           {"scenes", {{{"scene_id", 0}, {"description", "open"}, {"enter_time", 0}}}},
                           {"inputs", {{"net", {{"path", net_path}, {"sha256", ""}}}}},
                           {"actors", {{{"actor_id", 0}, {"length", 4.5}, {"width", 2.0}, {"ego", true}, {"color", ""}},
                                       {{"actor_id", 3}, {"length", 12.0}, {"width", 2.5}, {"ego", false}, {"color", "00ff00"}}}}};
  dir.write("result.json", result.dump());
  std::string trace = std::string(TraceWriter::kHeader) + "\n";
  for (int i = 1; i <= 3; ++i)
    for (int a : {0, 3})
      trace += fmt::format("{:.3f},0,{},{:.3f},{:.3f},0.0000,10.000,0.000,e0,0,{:.3f},0.000,0,0,script\n", 0.05 * i, a,
                           10.0 * i + a, 1.0 * a, 10.0 * i);
  dir.write("trace.csv", trace);
  dir.write("run.log", "t=    0.050  hello\n");
}

}  // namespace

TEST(CsvTable, ReadsColumnsCellsAndNumbersWithEmptyCellsAsNothing) {
  const auto t = CsvTable::parse("time,gap,ttc\n0.05,12.5,\n0.10,12.0,3.25\n", "m.csv", {"time", "ttc"});
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"time", "gap", "ttc"}));
  EXPECT_EQ(*t.number(1, *t.column("ttc")), 3.25);
  EXPECT_FALSE(t.number(0, *t.column("ttc")).has_value());
  EXPECT_FALSE(t.column("thw").has_value());
}

TEST(CsvTable, NamesTheFileLineAndColumnOfWhatIsWrong) {
  EXPECT_EQ(message_of([] { (void)CsvTable::parse("time,gap\n0.05,1\n0.10\n", "m.csv"); }),
            "m.csv:3: 1 cells, the header has 2 columns");
  EXPECT_EQ(message_of([] { (void)CsvTable::parse("time,gap\n", "m.csv", {"time", "ttc"}); }),
            "m.csv:1: no column \"ttc\" in the header (expected time,ttc)");
  const auto t = CsvTable::parse("time,gap\n0.05,near\n", "m.csv");
  EXPECT_EQ(message_of([&] { (void)t.number(0, 1); }), "m.csv:2: column gap: \"near\" is not a number");
  EXPECT_EQ(message_of([] { (void)CsvTable::parse("", "m.csv"); }), "m.csv:1: empty file, expected a header row");
}

TEST(RunFiles, OptionalFilesAreAbsentAndAMalformedOneIsAProblemNotACrash) {
  test::TempDir dir;
  write_run(dir, "");
  RunFiles f = read_run_files(dir.path());
  EXPECT_EQ(f.result["verdict"], "failure");
  ASSERT_TRUE(f.trace.has_value());
  EXPECT_EQ(f.trace->rows(), 6u);
  EXPECT_FALSE(f.metrics.has_value());
  EXPECT_FALSE(f.background.has_value());

  dir.write("metrics.csv", "time,actor_id\n0.05,0\n");  // not the evaluation's columns
  EXPECT_NE(message_of([&] { (void)read_run_files(dir.path()); }).find("metrics.csv:1: no column \"leader\""),
            std::string::npos);
  std::vector<std::string> problems;
  f = read_run_files(dir.path(), &problems);
  EXPECT_FALSE(f.metrics.has_value());
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("metrics.csv:1"), std::string::npos);

  dir.write("result.json", "{\"verdict\": \"success\",\n \"reason\": }");
  EXPECT_NE(message_of([&] { (void)read_run_files(dir.path()); }).find("result.json:2"), std::string::npos);
  fs::remove(dir / "result.json");
  EXPECT_NE(message_of([&] { (void)read_run_files(dir.path()); }).find("no such file"), std::string::npos);
}

TEST(NetShapes, NormalAndInternalLanesWithinTheBoundsAndNoWalkingAreas) {
  test::TempDir dir;
  const auto net = dir.write("n.net.xml", R"(<net version="1.9">
  <location netOffset="0.00,0.00" convBoundary="0,0,500,10"/>
  <edge id=":j_0" function="internal"><lane id=":j_0_0" index="0" width="3.50" shape="100.0,0.0 101.5,0.5 103.0,1.0"/></edge>
  <edge id=":j_w0" function="walkingarea"><lane id=":j_w0_0" index="0" shape="100,0 101,0 101,1"/></edge>
  <edge id="a" from="x" to="j"><lane id="a_0" index="0" shape="0.0,0.0 100.0,0.0"/><lane id="a_1" index="1" width="3.0" shape="0.0,3.2 100.0,3.2"/></edge>
  <edge id="far" from="j" to="y"><lane id="far_0" index="0" shape="400.0,0.0 500.0,0.0"/></edge>
</net>)");
  const auto lanes = report::read_lane_shapes(net, report::Bounds{-10, -10, 150, 20});
  ASSERT_EQ(lanes.size(), 3u);
  EXPECT_EQ(lanes[0].id, ":j_0_0");
  EXPECT_TRUE(lanes[0].internal);
  EXPECT_EQ(lanes[0].width, 3.5);
  EXPECT_EQ(lanes[0].xy, (std::vector<double>{100.0, 0.0, 101.5, 0.5, 103.0, 1.0}));
  EXPECT_EQ(lanes[1].width, 3.2) << "SUMO's default width";
  EXPECT_FALSE(lanes[1].internal);
  EXPECT_EQ(lanes[2].width, 3.0);
  EXPECT_EQ(report::read_lane_shapes(net, std::nullopt).size(), 4u);

  const auto bad = dir.write("bad.net.xml", R"(<net><edge id="a"><lane id="a_0" shape="0,0 1"/></edge></net>)");
  EXPECT_NE(message_of([&] { (void)report::read_lane_shapes(bad, std::nullopt); }).find("lane a_0: shape point \"1\""),
            std::string::npos);
  EXPECT_NE(message_of([&] { (void)report::read_lane_shapes(dir / "none.net.xml", std::nullopt); }).find("none.net.xml"),
            std::string::npos);
}

TEST(RunReportData, ActorsAsColumnsWithTheirSizesAndTheLanesAroundTheirPaths) {
  test::TempDir dir;
  const auto net = dir.write("n.net.xml", R"(<net>
  <edge id="near"><lane id="near_0" index="0" shape="0.0,0.0 50.0,0.0"/></edge>
  <edge id="far"><lane id="far_0" index="0" shape="5000.0,0.0 5100.0,0.0"/></edge></net>)");
  write_run(dir, net.string());
  const RunFiles f = read_run_files(dir.path());
  const auto data = report::run_report_data(f, {"a problem"});
  ASSERT_EQ(data["actors"].size(), 2u);
  const auto& ego = data["actors"][0];
  EXPECT_EQ(ego["actor_id"], 0);
  EXPECT_TRUE(ego["ego"].get<bool>());
  EXPECT_EQ(ego["time"], nlohmann::json({0.05, 0.1, 0.15}));
  EXPECT_EQ(ego["x"], nlohmann::json({10.0, 20.0, 30.0}));
  EXPECT_EQ(ego["length"], 4.5);
  const auto& bus = data["actors"][1];
  EXPECT_EQ(bus["x"], nlohmann::json({13.0, 23.0, 33.0}));
  EXPECT_EQ(bus["length"], 12.0);
  EXPECT_EQ(bus["color"], "#00ff00");
  ASSERT_EQ(data["lanes"].size(), 1u) << "only the lanes near the trajectories";
  EXPECT_EQ(data["lanes"][0]["id"], "near_0");
  EXPECT_TRUE(data["metrics"].is_null());
  EXPECT_EQ(data["problems"], nlohmann::json({"a problem"}));

  // The evaluation's metrics, per actor, when the run has them.
  dir.write("metrics.csv", metrics_csv({{{"time", "0.050"}, {"actor_id", "0"}, {"leader", "3"}, {"gap", "3.000"},
                                           {"rel_speed", "-1.0"}, {"ttc", "3.0"}, {"thw", "0.3"}, {"min_dist", "3.0"},
                                           {"min_dist_to", "3"}},
                                          {{"time", "0.100"}, {"actor_id", "0"}}}));
  const auto with = report::run_report_data(read_run_files(dir.path()), {});
  EXPECT_EQ(with["metrics"]["0"]["gap"], nlohmann::json({3.0, nullptr}));
  EXPECT_EQ(with["metrics"]["0"]["ttc"], nlohmann::json({3.0, nullptr}));

  // A net that is gone: the map is not drawn, and the report says why.
  fs::remove(net);
  const auto without = report::run_report_data(read_run_files(dir.path()), {});
  EXPECT_TRUE(without["lanes"].empty());
  ASSERT_EQ(without["problems"].size(), 1u);
  EXPECT_NE(without["problems"][0].get<std::string>().find("the map is not drawn"), std::string::npos);
}

TEST(RunReportPage, IsOneFileWhoseDataCannotEndItsScriptElement) {
  test::TempDir dir;
  write_run(dir, "");
  nlohmann::json result = test::read_json(dir / "result.json");
  result["title"] = "</script><script>alert(1)</script>";
  dir.write("result.json", result.dump());
  const fs::path page = report::write_run_report(dir.path());
  const std::string html = test::slurp(page);
  EXPECT_EQ(html.find("</script><script>alert(1)"), std::string::npos);
  EXPECT_NE(html.find("\\u003c/script>\\u003cscript>alert(1)"), std::string::npos);
  EXPECT_NE(html.find("Chart.js v3.9.1"), std::string::npos) << "Chart.js is inline";
  EXPECT_EQ(html.find("src=\"http"), std::string::npos) << "nothing from the network";
}
