// TrajectoryPosition (OpenSCENARIO 1.1: s along a trajectory, t to its left) and
// RelativeLanePosition's dsLane (1.1: the distance along the centre line of the reference
// entity's lane, not along the road's reference line).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "opendrive/xodr_reader.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "openscenario/xosc_reader.hpp"
#include "support/cli_runner.hpp"
#include "unit/openscenario_snippets.hpp"

namespace orch::openscenario {
namespace {

using test::kStraightTwoLaneRoad;
using test::place;
using test::vehicle;

// A left-turning arc of radius 100 m (curvature 0.01), two right lanes 3.5 m wide.
const std::string kArcRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="300" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="300"><arc curvature="0.01"/></geometry></planView>
<lanes><laneSection s="0"><right>
 <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";

class PositionKinds : public ::testing::Test {
 protected:
  // Entity A at s = 20 on lane -1 (at rest), B placed by `init_b`; no story.
  void load(const std::string& init_b, const std::string& road, const std::string& catalogs = "") {
    runtime_.reset();
    const std::string text = R"(<?xml version="1.0"?><OpenSCENARIO>
<FileHeader revMajor="1" revMinor="3" date="2024-01-01T00:00:00" author="t" description="positions"/>)" + catalogs +
                             R"(<RoadNetwork><LogicFile filepath="road.xodr"/></RoadNetwork>
<Entities>)" + vehicle("A") + vehicle("B") + R"(</Entities>
<Storyboard><Init><Actions>)" + place("A", 20, -1, 0) + init_b + R"(</Actions></Init>
<StopTrigger/></Storyboard></OpenSCENARIO>)";
    dir_.write("road.xodr", road);
    scenario_ = load_scenario(dir_.write("s.xosc", text).string());
    roads_ = opendrive::read_xodr_file((dir_ / "road.xodr").string());
    runtime_ = std::make_unique<StoryboardRuntime>(scenario_, roads_);  // runs Init
  }
  std::string load_error(const std::string& init_b, const std::string& road = kStraightTwoLaneRoad) {
    try {
      load(init_b, road);
    } catch (const ScenarioError& e) {
      return e.what();
    } catch (const MapError& e) {
      return e.what();
    }
    return "";
  }
  [[nodiscard]] const EntityState& b() const { return runtime_->entities().at("B"); }
  test::TempDir dir_;
  Scenario scenario_;
  opendrive::RoadNetwork roads_;
  std::unique_ptr<StoryboardRuntime> runtime_;
};

std::string teleport_b(const std::string& position) {
  return R"(<Private entityRef="B"><PrivateAction><TeleportAction><Position>)" + position +
         R"(</Position></TeleportAction></PrivateAction></Private>)";
}

// A polyline (0, -1.75) -> (100, -1.75) -> (100, 98.25): along lane -1, then a right angle left.
const std::string kPolyline = R"(<Trajectory name="Corner" closed="false"><Shape><Polyline>
<Vertex><Position><WorldPosition x="0" y="-1.75"/></Position></Vertex>
<Vertex><Position><WorldPosition x="100" y="-1.75"/></Position></Vertex>
<Vertex><Position><WorldPosition x="100" y="98.25"/></Position></Vertex></Polyline></Shape></Trajectory>)";

TEST_F(PositionKinds, TrajectoryPositionIsSAlongThePathAndTToItsLeft) {
  // s = 150: 50 m up the second leg (heading pi/2); t = 2 to its left is -x.
  load(teleport_b(R"(<TrajectoryPosition s="150" t="2"><TrajectoryRef>)" + kPolyline + "</TrajectoryRef></TrajectoryPosition>"),
       kStraightTwoLaneRoad);
  EXPECT_NEAR(b().pose.x, 98.0, 1e-9);
  EXPECT_NEAR(b().pose.y, 48.25, 1e-9);
  EXPECT_NEAR(b().pose.heading, std::numbers::pi / 2, 1e-9);
}

TEST_F(PositionKinds, TrajectoryPositionOnTheFirstLegLiesOnTheLaneAndTakesItsOrientation) {
  load(teleport_b(R"(<TrajectoryPosition s="60"><Orientation type="relative" h="0.1"/><TrajectoryRef>)" + kPolyline +
                  "</TrajectoryRef></TrajectoryPosition>"),
       kStraightTwoLaneRoad);
  EXPECT_NEAR(b().pose.x, 60.0, 1e-9);
  EXPECT_NEAR(b().pose.y, -1.75, 1e-9);
  EXPECT_NEAR(b().pose.heading, 0.1, 1e-9);
  EXPECT_EQ(b().lane, -1);
  EXPECT_NEAR(b().s, 60.0, 1e-6);
}

TEST_F(PositionKinds, TrajectoryPositionFollowsAClothoidAndVertexEntities) {
  // A clothoid starting at A (s = 20 on lane -1) with curvature 0 and no change: straight on,
  // so s = 30 along it is 30 m ahead of A.
  load(teleport_b(R"(<TrajectoryPosition s="30"><TrajectoryRef><Trajectory name="Ahead" closed="false"><Shape>
<Clothoid curvature="0" curvatureDot="0" length="50"><Position><RelativeObjectPosition entityRef="A" dx="0" dy="0"/></Position></Clothoid>
</Shape></Trajectory></TrajectoryRef></TrajectoryPosition>)"),
       kStraightTwoLaneRoad);
  EXPECT_NEAR(b().pose.x, 50.0, 1e-6);
  EXPECT_NEAR(b().pose.y, -1.75, 1e-6);
}

TEST_F(PositionKinds, TrajectoryPositionErrors) {
  EXPECT_NE(load_error(teleport_b(R"(<TrajectoryPosition s="250"><TrajectoryRef>)" + kPolyline +
                                  "</TrajectoryRef></TrajectoryPosition>"))
                .find("beyond the end of trajectory \"Corner\""),
            std::string::npos);
  EXPECT_NE(load_error(teleport_b(R"(<TrajectoryPosition s="-1"><TrajectoryRef>)" + kPolyline +
                                  "</TrajectoryRef></TrajectoryPosition>"))
                .find("cannot be negative"),
            std::string::npos);
  // A vertex relative to an entity that does not exist: found at load.
  EXPECT_NE(load_error(teleport_b(R"(<TrajectoryPosition s="1"><TrajectoryRef><Trajectory name="T" closed="false"><Shape><Polyline>
<Vertex><Position><RelativeObjectPosition entityRef="Nobody" dx="0" dy="0"/></Position></Vertex>
<Vertex><Position><WorldPosition x="100" y="-1.75"/></Position></Vertex></Polyline></Shape></Trajectory></TrajectoryRef></TrajectoryPosition>)"))
                .find("Nobody"),
            std::string::npos);
}

TEST_F(PositionKinds, DsLaneIsMeasuredAlongTheReferenceEntitysLaneCentre) {
  // A at s = 20 on lane -1 of the left arc: the lane centre lies 1.75 m outside the reference
  // line, radius 101.75, so 50 m along it is 50 * 100 / 101.75 m of s. Lane -2 (dLane -1)
  // at that s.
  load(teleport_b(R"(<RelativeLanePosition entityRef="A" dLane="-1" dsLane="50" offset="0"/>)"), kArcRoad);
  const double s = 20 + 50 * 100 / 101.75;
  EXPECT_NEAR(b().s, s, 1e-3);
  EXPECT_EQ(b().lane, -2);
  const opendrive::Pose2 expected = roads_.road("0").world(s, -5.25);
  EXPECT_NEAR(b().pose.x, expected.x, 1e-3);
  EXPECT_NEAR(b().pose.y, expected.y, 1e-3);
}

TEST_F(PositionKinds, DsLaneBackwardsAndDsStayTheirOwn) {
  load(teleport_b(R"(<RelativeLanePosition entityRef="A" dLane="0" dsLane="-10" offset="0"/>)"), kArcRoad);
  EXPECT_NEAR(b().s, 20 - 10 * 100 / 101.75, 1e-3);
  load(teleport_b(R"(<RelativeLanePosition entityRef="A" dLane="0" ds="-10" offset="0"/>)"), kArcRoad);
  EXPECT_NEAR(b().s, 10, 1e-6);
}

TEST_F(PositionKinds, DsAndDsLaneAreMutuallyExclusive) {
  EXPECT_NE(load_error(teleport_b(R"(<RelativeLanePosition entityRef="A" dLane="0" ds="1" dsLane="1"/>)"))
                .find("mutually exclusive"),
            std::string::npos);
  EXPECT_NE(load_error(teleport_b(R"(<RelativeLanePosition entityRef="A" dLane="0"/>)")).find("ds or dsLane"),
            std::string::npos);
  EXPECT_NE(load_error(teleport_b(R"(<RelativeLanePosition entityRef="A" dLane="0" dsLane="5000"/>)")).find("leaves road"),
            std::string::npos);
}

}  // namespace
}  // namespace orch::openscenario
