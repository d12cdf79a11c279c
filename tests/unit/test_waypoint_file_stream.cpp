// The streaming reader of waypoint files gives exactly what the reader with messages gives
// for every well-formed file, and gives up (so that the reader with messages names the
// problem) on anything else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "map/waypoint_file_stream.hpp"
#include "unit/synthetic_roads.hpp"

namespace {

using orch::WaypointFile;

void expect_same(const WaypointFile& a, const WaypointFile& b) {
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.map_id, b.map_id);
  ASSERT_EQ(a.routes.size(), b.routes.size());
  for (std::size_t r = 0; r < a.routes.size(); ++r) {
    const auto& ra = a.routes[r];
    const auto& rb = b.routes[r];
    EXPECT_EQ(ra.id, rb.id);
    ASSERT_EQ(ra.points.size(), rb.points.size()) << ra.id;
    for (std::size_t k = 0; k < ra.points.size(); ++k) {
      // Bit for bit: both readers convert the same parsed numbers the same way.
      EXPECT_EQ(ra.points[k].x, rb.points[k].x);
      EXPECT_EQ(ra.points[k].y, rb.points[k].y);
      EXPECT_EQ(ra.points[k].height, rb.points[k].height);
      EXPECT_EQ(ra.points[k].v, rb.points[k].v);
    }
    EXPECT_EQ(ra.line.length(), rb.line.length());
  }
  ASSERT_EQ(a.properties.size(), b.properties.size());
  for (std::size_t p = 0; p < a.properties.size(); ++p) {
    EXPECT_EQ(a.properties[p].id, b.properties[p].id);
    EXPECT_EQ(a.properties[p].name, b.properties[p].name);
    EXPECT_EQ(a.properties[p].index, b.properties[p].index);
    EXPECT_EQ(a.properties[p].waypoint_id, b.properties[p].waypoint_id);
  }
}

std::vector<std::filesystem::path> project_waypoint_files() {
  std::vector<std::filesystem::path> files;
  for (const auto* dir : {"sumo_nets", "tests/data/waypoints"})
    for (const auto& e : std::filesystem::recursive_directory_iterator(std::filesystem::path(ORCH_SOURCE_DIR) / dir))
      if (e.path().string().ends_with(".waypoint.json")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(WaypointFileStream, GivesWhatTheReaderWithMessagesGivesForEveryShippedFile) {
  const auto files = project_waypoint_files();
  ASSERT_GE(files.size(), 5u);  // four shipped maps and the junction fixtures
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    const auto fast = orch::read_well_formed_waypoint_file(f.string());
    ASSERT_TRUE(fast.has_value());
    expect_same(*fast, orch::read_waypoint_file_with_messages(f.string()));
  }
}

constexpr const char* kWellFormed = R"({"id": "W", "mapId": "M", "waypoints": [
  {"id": "a", "points": [{"x": 1, "y": 0.5, "z": 2, "v": 36}, {"z": -3.25, "x": 4e1}]},
  {"id": "b", "points": [{"x": 0, "z": 0}, {"x": 0, "z": 10, "v": 50}]}],
  "properties": [{"id": "p", "name": "n", "index": 3, "waypointId": "a"}]})";

TEST(WaypointFileStream, ReadsEveryFieldInAnyKeyOrder) {
  orch::test::TempDir dir("waypoint_stream");
  const auto path = (dir.path() / "w.json").string();
  std::ofstream(path) << kWellFormed;
  const auto fast = orch::read_well_formed_waypoint_file(path);
  ASSERT_TRUE(fast.has_value());
  ASSERT_EQ(fast->routes.size(), 2u);
  EXPECT_DOUBLE_EQ(fast->routes[0].points[1].x, 40.0);
  EXPECT_DOUBLE_EQ(fast->routes[0].points[1].y, 3.25);
  EXPECT_DOUBLE_EQ(fast->routes[0].points[0].v, 10.0);
  ASSERT_EQ(fast->properties.size(), 1u);
  EXPECT_EQ(fast->properties[0].waypoint_id, "a");
  expect_same(*fast, orch::read_waypoint_file_with_messages(path));
}

TEST(WaypointFileStream, GivesUpOnWhatAWellFormedFileDoesNotHave) {
  const std::string base = kWellFormed;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = base;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::vector<std::pair<std::string, std::string>> damaged = {
      {"unknown key", replaced("\"v\": 36", "\"w\": 36")},
      {"repeated key", replaced("\"v\": 36", "\"v\": 36, \"v\": 37")},
      {"text for a number", replaced("\"x\": 1,", "\"x\": \"1\",")},
      {"null", replaced("\"y\": 0.5", "\"y\": null")},
      {"missing z", replaced(", \"z\": 2", "")},
      {"one point", replaced("{\"x\": 0, \"z\": 0}, ", "")},
      {"repeated route id", replaced("\"id\": \"b\"", "\"id\": \"a\"")},
      {"number beyond double", replaced("4e1", "4e400")},
      {"nested deeper", replaced("\"v\": 50", "\"v\": [50]")},
      {"truncated", base.substr(0, base.size() - 3)},
      {"no routes", R"({"waypoints": []})"},
      {"not an object", "[]"},
      {"invalid UTF-8", replaced("\"name\": \"n\"", "\"name\": \"\xff\"")},
  };
  orch::test::TempDir dir("waypoint_stream");
  for (const auto& [what, text] : damaged) {
    SCOPED_TRACE(what);
    const auto path = (dir.path() / "w.json").string();
    std::ofstream(path, std::ios::trunc) << text;
    EXPECT_FALSE(orch::read_well_formed_waypoint_file(path).has_value());
    EXPECT_THROW(orch::load_waypoint_file(path), orch::ScenarioError);  // the reader with messages names it
  }
  EXPECT_FALSE(orch::read_well_formed_waypoint_file((dir.path() / "missing.json").string()).has_value());
  EXPECT_FALSE(orch::read_well_formed_waypoint_file(dir.path().string()).has_value());
}

}  // namespace
