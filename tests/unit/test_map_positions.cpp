// The ScenarioExecutor positions resolved by map/'s position resolver on a RoadEditor
// waypoint file (routes built here), and the error for a position of the other language's
// geometry. (OpenSCENARIO positions: test_openscenario_positions.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/errors.hpp"
#include "map/position_resolver.hpp"

namespace orch::position {
namespace {

// Route "A": along +x from (0, 0) to (100, 0), points every 10 m; route "B": along +y from
// (50, -50) to (50, 50), points every 25 m.
WaypointFile two_routes() {
  WaypointFile file;
  const auto route = [](const std::string& id, Vec2 from, Vec2 step, int n) {
    WaypointRoute r;
    r.id = id;
    std::vector<Vec2> line;
    for (int i = 0; i <= n; ++i) {
      const Vec2 p = from + step * i;
      r.points.push_back({p.x(), p.y(), 0.0, 10.0});
      line.push_back(p);
    }
    r.line = Polyline(line);
    return r;
  };
  file.routes.push_back(route("A", {0, 0}, {10, 0}, 10));
  file.routes.push_back(route("B", {50, -50}, {0, 25}, 4));
  return file;
}

class Actors final : public Entities {
 public:
  explicit Actors(const WaypointFile& file) : file_(file) {}
  [[nodiscard]] std::optional<opendrive::Pose2> pose(const std::string& name) const override {
    if (name == "1") return opendrive::Pose2{30.0, 2.0, 0.0};  // beside route A at s = 30
    return std::nullopt;
  }
  [[nodiscard]] const WaypointRoute* route(const std::string& name) const override {
    return name == "1" ? file_.find("A") : nullptr;
  }
  [[nodiscard]] double length(const std::string& name) const override { return name == "1" ? 4.0 : 0.0; }

 private:
  const WaypointFile& file_;
};

TEST(MapPositions, WaypointRefIsTheRoutePointAtItsFractionalIndex) {
  const WaypointFile file = two_routes();
  const PositionResolver resolver(file);
  const ResolvedPosition r = resolver.resolve(WaypointRef{"A", 3.25, {}}, Actors(file));
  ASSERT_TRUE(r.route.has_value());
  EXPECT_EQ(r.route->route, file.find("A"));
  EXPECT_NEAR(r.route->s, 32.5, 1e-9);
  EXPECT_NEAR(r.pose.x, 32.5, 1e-9);
  EXPECT_NEAR(r.pose.y, 0.0, 1e-9);
  EXPECT_NEAR(r.pose.heading, 0.0, 1e-9);
  EXPECT_FALSE(r.road.has_value());
  // Past the route's end: its last point.
  EXPECT_NEAR(resolver.resolve(WaypointRef{"B", 9, {}}, Actors(file)).pose.y, 50.0, 1e-9);
  EXPECT_NEAR(resolver.resolve(WaypointRef{"B", 9, {}}, Actors(file)).pose.heading, M_PI / 2, 1e-9);
}

TEST(MapPositions, RouteDistanceFromTheTargetsNearestRoutePoint) {
  const WaypointFile file = two_routes();
  const PositionResolver resolver(file);
  const Actors actors(file);
  // On the target's own route: 20 m ahead of s = 30.
  EXPECT_NEAR(resolver.resolve(RouteDistance{"1", 20.0, false, std::nullopt}, actors).route->s, 50.0, 1e-9);
  // Surface to surface: half of both lengths (5 m and 4 m) further, behind it.
  const ResolvedPosition behind = resolver.resolve(RouteDistance{"1", -10.0, true, std::nullopt}, actors, 5.0);
  EXPECT_NEAR(behind.route->s, 30.0 - 10.0 - 4.5, 1e-9);
  EXPECT_NEAR(behind.pose.x, 15.5, 1e-9);
  // Along another route: from the point of route B nearest the target (50, 2), 10 m on.
  const ResolvedPosition on_b = resolver.resolve(RouteDistance{"1", 10.0, false, WaypointRef{"B", 0, {}}}, actors);
  EXPECT_EQ(on_b.route->route, file.find("B"));
  EXPECT_NEAR(on_b.pose.x, 50.0, 1e-9);
  EXPECT_NEAR(on_b.pose.y, 12.0, 1e-9);  // the point of B nearest (30, 2) is (50, 2)
}

TEST(MapPositions, MissingRoutesActorsAndGeometryAreClearErrors) {
  const WaypointFile file = two_routes();
  const PositionResolver resolver(file);
  const Actors actors(file);
  try {
    (void)resolver.resolve(WaypointRef{"C", 0, SourceLocation{"s.json", "/x", 7}}, actors);
    FAIL() << "no error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("no route \"C\""), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)resolver.resolve(RouteDistance{"2", 5.0, false, std::nullopt}, actors), MapError);
  try {
    (void)resolver.resolve(LanePosition{"0", -1, 10.0, 0.0, std::nullopt}, actors);
    FAIL() << "no error";
  } catch (const MapError& e) {
    EXPECT_NE(std::string(e.what()).find("needs OpenDRIVE roads"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orch::position
