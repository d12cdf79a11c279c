// Roads with elevation and superelevation (opendrive/road_network.hpp): the height of a point,
// the attitude of a body on the surface, t along the rolled surface (its projected offset
// shrinks by cos(roll), OpenDRIVE 1.6 8.4.1), and the reader's limits, and a lane's own height (a curb).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "opendrive/road_network.hpp"
#include "opendrive/xodr_reader.hpp"

using namespace orch::opendrive;

namespace {

// A straight 200 m road along x with two right lanes of 3.5 m; PROFILES goes inside <road>.
std::string road_with(const std::string& profiles) {
  return R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="1" length="200" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
)" + profiles + R"(
<lanes><laneSection s="0"><right>
<lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
<lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";
}

}  // namespace

TEST(OpenDriveElevation, HeightAndPitchFollowTheElevationProfile) {
  // Flat for 100 m, then a 5 % climb: z = 0.05 (s - 100).
  const RoadNetwork net = read_xodr_text(
      road_with(R"(<elevationProfile><elevation s="0" a="0" b="0" c="0" d="0"/>
<elevation s="100" a="0" b="0.05" c="0" d="0"/></elevationProfile>)"),
      "hill.xodr");
  const Road& road = net.road("1");
  EXPECT_DOUBLE_EQ(road.elevation(50), 0.0);
  EXPECT_NEAR(road.elevation(150), 2.5, 1e-12);
  const SurfacePose up = surface_pose(road, 150, -1.75, 0.0);
  EXPECT_NEAR(up.z, 2.5, 1e-12);
  EXPECT_NEAR(up.pitch, -std::atan(0.05), 1e-12);  // climbing: nose up, pitch negative (ISO 8855)
  EXPECT_NEAR(up.roll, 0.0, 1e-12);
  // Facing the other way, the same slope is a descent; across the road, it is a roll.
  EXPECT_NEAR(surface_pose(road, 150, -1.75, std::numbers::pi).pitch, std::atan(0.05), 1e-12);
  const SurfacePose across = surface_pose(road, 150, -1.75, std::numbers::pi / 2);
  EXPECT_NEAR(across.pitch, 0.0, 1e-12);
  // Facing +y the body's left side points downhill (-x): left side down, a negative roll.
  EXPECT_NEAR(across.roll, -std::atan(0.05), 1e-12);
}

TEST(OpenDriveElevation, SuperelevationRollsTheCrossSectionAboutTheReferenceLine) {
  // Falling to the right by 30 degrees: a point 3.5 m to the right along the surface lies
  // 3.5 cos 30 = 3.03 m to the side and 3.5 sin 30 = 1.75 m lower.
  const double roll = std::numbers::pi / 6;
  const RoadNetwork net = read_xodr_text(
      road_with(R"(<lateralProfile><superelevation s="0" a=")" + std::to_string(roll) + R"(" b="0" c="0" d="0"/></lateralProfile>)"),
      "banked.xodr");
  const Road& road = net.road("1");
  const Pose2 p = road.world(100, -3.5);
  EXPECT_NEAR(p.x, 100.0, 1e-9);
  EXPECT_NEAR(p.y, -3.5 * std::cos(roll), 1e-6);
  EXPECT_NEAR(road.height(100, -3.5), -1.75, 1e-6);
  const SurfacePose body = surface_pose(road, 100, -3.5, 0.0);
  EXPECT_NEAR(body.roll, roll, 1e-6);
  EXPECT_NEAR(body.pitch, 0.0, 1e-12);
  // Back from the plane to the road: t along the surface again, on lane -1's outer border.
  const RoadCoordinate c = project(road, p.x, p.y);
  EXPECT_NEAR(c.t, -3.5, 1e-6);
  EXPECT_EQ(road.lane_at(100, -5.0), -2);
}

TEST(OpenDriveElevation, TheReaderRefusesHeightsAndRollsNoRoadHas) {
  const auto error_of = [](const std::string& profiles) -> std::string {
    try {
      (void)read_xodr_text(road_with(profiles), "r.xodr");
    } catch (const orch::ScenarioError& e) {
      return e.what();
    }
    return "read";
  };
  EXPECT_NE(error_of(R"(<elevationProfile><elevation s="0" a="0" b="1e4" c="0" d="0"/></elevationProfile>)")
                .find("the road's height reaches 2e+06 m"),
            std::string::npos)
      << error_of(R"(<elevationProfile><elevation s="0" a="0" b="1e4" c="0" d="0"/></elevationProfile>)");
  EXPECT_NE(error_of(R"(<lateralProfile><superelevation s="0" a="1.5" b="0" c="0" d="0"/></lateralProfile>)")
                .find("the road's roll reaches 1.5 rad"),
            std::string::npos);
  // A velodrome's 60 degrees and a mountain pass at 2,400 m read.
  EXPECT_EQ(error_of(R"(<lateralProfile><superelevation s="0" a="-1.0471975511965976" b="0" c="0" d="0"/></lateralProfile>
<elevationProfile><elevation s="0" a="2400" b="0.08" c="0" d="0"/></elevationProfile>)"),
            "read");
}

TEST(OpenDriveElevation, LaneHeightRaisesItsLaneFromTheInnerToTheOuterBorder) {
  // A curb: lane -2 (t in [-7, -3.5]) rises from 0.10 m at its inner border to 0.16 m at
  // its outer one from s = 50 on (OpenDRIVE 1.6, 9.5.7); lane -1 and s < 50 stay on the road.
  const RoadNetwork net = read_xodr_text(R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="1" length="200" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
<elevationProfile><elevation s="0" a="1" b="0" c="0" d="0"/></elevationProfile>
<lanes><laneSection s="0"><right>
<lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
<lane id="-2" type="sidewalk"><width sOffset="0" a="3.5" b="0" c="0" d="0"/>
<height sOffset="50" inner="0.10" outer="0.16"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)",
                                         "curb.xodr");
  const Road& road = net.road("1");
  EXPECT_NEAR(road.height(100, -1.75), 1.0, 1e-12);
  EXPECT_NEAR(road.height(20, -5.25), 1.0, 1e-12);
  EXPECT_NEAR(road.height(100, -3.5 - 1e-9), 1.10, 1e-6);
  EXPECT_NEAR(road.height(100, -5.25), 1.13, 1e-12);
  EXPECT_NEAR(road.height(100, -7.0), 1.16, 1e-12);
  EXPECT_NEAR(surface_pose(road, 100, -5.25, 0.0).z, 1.13, 1e-12);
}

TEST(OpenDriveElevation, TheReaderRefusesALaneHeightNoCurbHas) {
  try {
    (void)read_xodr_text(R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="1" length="200" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry></planView>
<lanes><laneSection s="0"><right>
<lane id="-1" type="sidewalk"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><height sOffset="0" inner="0" outer="3e5"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)",
                         "curb.xodr");
    FAIL() << "read";
  } catch (const orch::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("lane height 300000 m"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outer"), std::string::npos) << e.what();
  }
}
