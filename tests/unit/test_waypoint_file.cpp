// Loading RoadEditor waypoint files: the coordinate transform, units, and errors that point
// at the line of the problem.
#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.hpp"
#include "map/waypoint_file.hpp"
#include "unit/synthetic_roads.hpp"

using orch::load_waypoint_file;
using orch::ScenarioError;
using orch::test::TempDir;

namespace {

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const auto path = dir.path() / name;
  std::ofstream(path) << text;
  return path.string();
}

// The messages of a ScenarioError thrown by loading `path` ("" when it loads).
std::vector<orch::Diagnostic> load_errors(const std::string& path) {
  try {
    load_waypoint_file(path);
  } catch (const ScenarioError& e) {
    return e.diagnostics().items();
  }
  return {};
}

constexpr const char* kTwoRoutes = R"({
  "id": "WayPoint_Test.Road",
  "mapId": "Test.Road",
  "waypoints": [
    {"id": "Waypoint01", "points": [
      {"x": 10, "y": 0.5, "z": 4.5, "v": 36},
      {"x": 11, "y": 0.5, "z": 4.5, "v": 72},
      {"x": 13, "y": 0.5, "z": 4.5, "v": 72}]},
    {"id": "Waypoint02", "points": [
      {"x": 0, "y": 0, "z": -3, "v": 90},
      {"x": 0, "y": 0, "z": -7, "v": 90}]}
  ],
  "properties": [{"id": "ego_startPoint", "name": "start", "index": 1, "waypointId": "Waypoint02"}]
})";

}  // namespace

TEST(WaypointFile, ConvertsThreeJsCoordinatesAndSpeeds) {
  TempDir dir("wpfile");
  const auto file = load_waypoint_file(write(dir, "ok.json", kTwoRoutes));
  EXPECT_EQ(file.id, "WayPoint_Test.Road");
  EXPECT_EQ(file.map_id, "Test.Road");
  ASSERT_EQ(file.routes.size(), 2u);
  const auto& r = file.routes[0];
  ASSERT_EQ(r.points.size(), 3u);
  // map x = x, map y = -z, height = y.
  EXPECT_DOUBLE_EQ(r.points[0].x, 10.0);
  EXPECT_DOUBLE_EQ(r.points[0].y, -4.5);
  EXPECT_DOUBLE_EQ(r.points[0].height, 0.5);
  // km/h -> m/s.
  EXPECT_DOUBLE_EQ(r.points[0].v, 10.0);
  EXPECT_DOUBLE_EQ(r.points[1].v, 20.0);
  // The route line is the points in the map frame; z = -3 -> -7 drives towards +y.
  const auto& r2 = *file.find("Waypoint02");
  EXPECT_TRUE(r2.line.point(1).isApprox(orch::Vec2(0, 7)));
  EXPECT_NEAR(r2.line.heading_at(1.0), std::acos(0.0), 1e-12);
  EXPECT_DOUBLE_EQ(r.line.length(), 3.0);
  EXPECT_DOUBLE_EQ(r.s_of(1.5), 2.0);
  EXPECT_DOUBLE_EQ(r.speed_at(0.5), 10.0);
  EXPECT_DOUBLE_EQ(r.speed_at(2.5), 20.0);
  EXPECT_EQ(file.route_ids(), (std::vector<std::string>{"Waypoint01", "Waypoint02"}));
  EXPECT_EQ(file.find("Waypoint03"), nullptr);
  ASSERT_EQ(file.properties.size(), 1u);
  EXPECT_EQ(file.properties[0].waypoint_id, "Waypoint02");
  EXPECT_DOUBLE_EQ(file.properties[0].index, 1.0);
}

TEST(WaypointFile, MissingCoordinateIsReportedAtItsLine) {
  TempDir dir("wpfile");
  std::string text = kTwoRoutes;
  // Line 7 of the text: the second point of Waypoint01 loses its "z".
  const std::string point = R"({"x": 11, "y": 0.5, "z": 4.5, "v": 72})";
  const auto at = text.find(point);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, point.size(), R"({"x": 11, "y": 0.5, "v": 72})");
  const auto errors = load_errors(write(dir, "broken.json", text));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].where.line, 7);
  EXPECT_EQ(errors[0].where.pointer, "/waypoints/0/points/1");
  EXPECT_NE(errors[0].message.find("z"), std::string::npos) << errors[0].message;
  EXPECT_NE(errors[0].format().find("broken.json:7"), std::string::npos) << errors[0].format();
}

TEST(WaypointFile, SyntaxErrorNamesTheLine) {
  TempDir dir("wpfile");
  std::string text = kTwoRoutes;
  const std::string end_of_point = R"("v": 90},)";
  text.replace(text.find(end_of_point), end_of_point.size(), R"("v": 90}},)");  // line 10: one brace too many
  const auto errors = load_errors(write(dir, "syntax.json", text));
  ASSERT_FALSE(errors.empty());
  EXPECT_EQ(errors[0].where.line, 10) << errors[0].format();
}

TEST(WaypointFile, RejectsRoutesThatCannotBeLanes) {
  TempDir dir("wpfile");
  const auto one_point = load_errors(write(dir, "one.json", R"({"waypoints": [
    {"id": "A", "points": [{"x": 0, "z": 0}]}]})"));
  ASSERT_EQ(one_point.size(), 1u);
  EXPECT_NE(one_point[0].message.find("at least two points"), std::string::npos);
  EXPECT_EQ(one_point[0].where.line, 2);

  const auto same_place = load_errors(write(dir, "same.json", R"({"waypoints": [
    {"id": "A", "points": [{"x": 1, "z": 1}, {"x": 1, "z": 1}]}]})"));
  ASSERT_EQ(same_place.size(), 1u);
  EXPECT_NE(same_place[0].message.find("one place"), std::string::npos);

  const auto twice = load_errors(write(dir, "twice.json", R"({"waypoints": [
    {"id": "A", "points": [{"x": 0, "z": 0}, {"x": 1, "z": 0}]},
    {"id": "A", "points": [{"x": 0, "z": 3}, {"x": 1, "z": 3}]}]})"));
  ASSERT_EQ(twice.size(), 1u);
  EXPECT_EQ(twice[0].where.line, 3);
  EXPECT_NE(twice[0].message.find("used twice"), std::string::npos);

  EXPECT_FALSE(load_errors(write(dir, "empty.json", R"({"waypoints": []})")).empty());
  EXPECT_FALSE(load_errors((dir.path() / "missing.json").string()).empty());
}

TEST(WaypointFile, SyntheticWriterRoundTrips) {
  // The files the map tests generate load as intended (y = -z applied twice is identity).
  TempDir dir("wpfile");
  orch::test::RoadShape road;
  road.straight = 100;
  road.radius = -200;
  road.arc_length = 50;
  const auto path = orch::test::write_waypoint_file(
      dir.path(), "synthetic", {{"R", orch::test::road_points(road, 1.75, 0, 150), 50}});
  const auto file = load_waypoint_file(path.string());
  ASSERT_EQ(file.routes[0].points.size(), 151u);
  EXPECT_TRUE(file.routes[0].line.point(150).isApprox(road.at(150, 1.75), 1e-9));
  EXPECT_NEAR(file.routes[0].points[0].v, 50 / 3.6, 1e-12);
  // The arc turns right: 49.5 m into it the heading is 49.5 / -200 rad.
  EXPECT_NEAR(file.routes[0].line.heading_at(149.5), 49.5 / -200.0, 1e-4);
}
