// OpenSCENARIO's GeoPosition: the projection through an OpenDRIVE geoReference and header
// offset (opendrive/geo_projection.hpp), its reading (degrees, radians) and an entity placed
// by it. SUMO's own conversion of the same road is the independent check
// (tests/integration/test_geo_position.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "opendrive/geo_projection.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch {
namespace {

using opendrive::GeoPoint;
using opendrive::GeoProjection;
using opendrive::GeoReference;

const std::string kTmerc = "+proj=tmerc +lat_0=48.1 +lon_0=11.5 +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs";

TEST(GeoProjection, TheProjectionOriginIsTheLocalOriginAndNorthIsPlusY) {
  const GeoProjection p(GeoReference{kTmerc});
  const Vec2 origin = p.local({48.1, 11.5});
  EXPECT_NEAR(origin.x(), 0.0, 1e-6);
  EXPECT_NEAR(origin.y(), 0.0, 1e-6);
  // A thousandth of a degree north on the central meridian: straight up the y axis, about
  // 111 m (a degree of latitude is 111.2 km at 48 degrees).
  const Vec2 north = p.local({48.101, 11.5});
  EXPECT_NEAR(north.x(), 0.0, 1e-6);
  EXPECT_GT(north.y(), 110.9);
  EXPECT_LT(north.y(), 111.5);
  const Vec2 east = p.local({48.1, 11.501});
  EXPECT_GT(east.x(), 74.0);  // 111.3 km * cos(48.1 deg) per degree of longitude
  EXPECT_LT(east.x(), 74.6);
}

TEST(GeoProjection, LocalAndGeographicAreInverse) {
  const GeoProjection p(GeoReference{kTmerc, 120.0, -40.0, 0.0, 0.4});
  for (const Vec2& local : {Vec2{0, 0}, Vec2{250.5, -13.25}, Vec2{-1800, 2400}}) {
    const Vec2 back = p.local(p.geographic(local));
    EXPECT_NEAR(back.x(), local.x(), 1e-6);
    EXPECT_NEAR(back.y(), local.y(), 1e-6);
  }
}

TEST(GeoProjection, TheHeaderOffsetMovesAndTurnsTheLocalFrameAsOpenDriveSays) {
  // OpenDRIVE 1.6, 8.5: world = R(hdg) * local + (x, y).
  const GeoProjection plain(GeoReference{kTmerc});
  const GeoProjection moved(GeoReference{kTmerc, 100.0, -50.0, 2.0, 0.3});
  const GeoPoint point{48.1021, 11.4987};
  const Vec2 world = plain.local(point);
  const Vec2 local = moved.local(point);
  const double c = std::cos(0.3), s = std::sin(0.3);
  EXPECT_NEAR(c * local.x() - s * local.y() + 100.0, world.x(), 1e-6);
  EXPECT_NEAR(s * local.x() + c * local.y() - 50.0, world.y(), 1e-6);
}

TEST(GeoProjection, ACrsIsReachedFromWgs84) {
  // UTM zone 32N: its central meridian (9 degrees east) lies at the false easting, 500 km.
  const GeoProjection utm(GeoReference{"EPSG:32632"});
  const Vec2 p = utm.local({48.0, 9.0});
  EXPECT_NEAR(p.x(), 500000.0, 1e-3);
  EXPECT_GT(p.y(), 5.3e6);
  const GeoPoint back = utm.geographic(p);
  EXPECT_NEAR(back.latitude_deg, 48.0, 1e-9);
  EXPECT_NEAR(back.longitude_deg, 9.0, 1e-9);
}

TEST(GeoProjection, NoOrABadGeoReferenceIsAnErrorNamingIt) {
  try {
    const GeoProjection p(GeoReference{});
    FAIL() << "no error";
  } catch (const MapError& e) {
    EXPECT_NE(std::string(e.what()).find("has no geoReference"), std::string::npos) << e.what();
  }
  try {
    const GeoProjection p(GeoReference{"+proj=nosuchprojection +ellps=WGS84"});
    FAIL() << "no error";
  } catch (const MapError& e) {
    EXPECT_NE(std::string(e.what()).find("geoReference \"+proj=nosuchprojection +ellps=WGS84\": PROJ cannot read it"),
              std::string::npos)
        << e.what();
  }
}

// A straight road along x with kTmerc as its geoReference (and an offset when asked).
std::string geo_road(const std::string& offset = "") {
  std::string road = test::kStraightTwoLaneRoad;
  const std::string header = R"(<header revMajor="1" revMinor="6"/>)";
  road.replace(road.find(header), header.size(),
               R"(<header revMajor="1" revMinor="6"><geoReference><![CDATA[ )" + kTmerc + " ]]></geoReference>" + offset +
                   "</header>");
  return road;
}

class GeoPositions : public ::testing::Test {
 protected:
  // A scenario whose car A is teleported to `position` (the inner XML of Position).
  void load(const std::string& position, const std::string& road) {
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="2" date="2024-01-01T00:00:00" author="t" description="geo"/>
<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + test::vehicle("A") + R"(</Entities>
<Storyboard><Init><Actions><Private entityRef="A"><PrivateAction><TeleportAction><Position>)" +
                             position + R"(</Position></TeleportAction></PrivateAction></Private></Actions></Init>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", road);
    scenario_ = openscenario::load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<openscenario::StoryboardRuntime>(scenario_, roads_);
    runtime_->step(0.05);
  }
  std::string load_error(const std::string& position, const std::string& road) {
    try {
      load(position, road);
    } catch (const OrchError& e) {
      return e.what();
    }
    return "no error";
  }
  [[nodiscard]] const opendrive::Pose2& pose() const { return runtime_->entities().at("A").pose; }
  test::TempDir dir_;
  openscenario::Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<openscenario::StoryboardRuntime> runtime_;
};

TEST_F(GeoPositions, DegreesAndRadiansPlaceTheCarWhereTheProjectionSays) {
  const std::string offset = R"(<offset x="-30" y="4" z="0" hdg="0"/>)";
  const GeoProjection projection(GeoReference{kTmerc, -30.0, 4.0});
  const GeoPoint on_lane = projection.geographic(Vec2{40.0, -1.75});  // lane -1's centre at s = 40
  load(fmt::format(R"(<GeoPosition latitudeDeg="{:.12f}" longitudeDeg="{:.12f}"/>)", on_lane.latitude_deg,
                   on_lane.longitude_deg),
       geo_road(offset));
  EXPECT_NEAR(pose().x, 40.0, 1e-4);
  EXPECT_NEAR(pose().y, -1.75, 1e-4);
  EXPECT_NEAR(pose().heading, 0.0, 1e-9);  // no Orientation: along the road
  EXPECT_EQ(runtime_->entities().at("A").lane, -1);
  // 1.0 / 1.1: radians; an absolute Orientation gives the heading as it is.
  constexpr double kToRad = std::numbers::pi / 180.0;
  load(fmt::format(R"(<GeoPosition latitude="{:.15f}" longitude="{:.15f}" height="0"><Orientation type="absolute" h="0.5"/></GeoPosition>)",
                   on_lane.latitude_deg * kToRad, on_lane.longitude_deg * kToRad),
       geo_road(offset));
  EXPECT_NEAR(pose().x, 40.0, 1e-4);
  EXPECT_NEAR(pose().y, -1.75, 1e-4);
  EXPECT_NEAR(pose().heading, 0.5, 1e-9);
}

TEST_F(GeoPositions, ReadingErrorsNameTheAttribute) {
  EXPECT_NE(load_error(R"(<GeoPosition latitudeDeg="95" longitudeDeg="11.5"/>)", geo_road())
                .find("95 degrees is outside [-90, 90]"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<GeoPosition latitudeDeg="48.1" latitude="0.84" longitudeDeg="11.5"/>)", geo_road())
                .find("latitudeDeg and latitude give the same angle twice"),
            std::string::npos);
  EXPECT_NE(load_error(R"(<GeoPosition latitudeDeg="48.1"/>)", geo_road()).find("a GeoPosition needs longitudeDeg"),
            std::string::npos);
  // A road that is not on the earth: the run cannot place the car, and says why.
  EXPECT_NE(load_error(R"(<GeoPosition latitudeDeg="48.1" longitudeDeg="11.5"/>)", test::kStraightTwoLaneRoad)
                .find("has no geoReference"),
            std::string::npos);
}

}  // namespace
}  // namespace orch
