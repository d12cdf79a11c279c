// OpenDRIVE planView geometry against values computed independently of the evaluator:
// closed forms for lines, arcs and straight polynomials; a spiral against a fine midpoint
// integration; lanes against hand-summed widths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "opendrive/road_network.hpp"
#include "opendrive/xodr_reader.hpp"

namespace orch::opendrive {
namespace {

Geometry at(double x, double y, double hdg, double length, Shape shape) {
  return Geometry{0.0, {x, y, hdg}, length, shape};
}

TEST(OpenDriveGeometry, LineMovesAlongItsHeading) {
  const Geometry g = at(10.0, -5.0, 0.6, 100.0, Line{});
  const Pose2 p = evaluate(g, 42.0);
  EXPECT_NEAR(p.x, 10.0 + 42.0 * std::cos(0.6), 1e-12);
  EXPECT_NEAR(p.y, -5.0 + 42.0 * std::sin(0.6), 1e-12);
  EXPECT_NEAR(p.heading, 0.6, 1e-12);
}

TEST(OpenDriveGeometry, ArcFollowsItsCircle) {
  for (const double k : {0.004, -0.004, 0.05}) {
    const double h0 = 0.3;
    const Geometry g = at(1.0, 2.0, h0, 200.0, Arc{k});
    const double r = 1.0 / k;
    // Centre of the circle: r to the left of the start pose.
    const double cx = 1.0 - r * std::sin(h0);
    const double cy = 2.0 + r * std::cos(h0);
    for (const double ds : {0.0, 17.5, 123.0, 200.0}) {
      const Pose2 p = evaluate(g, ds);
      const double h = h0 + k * ds;
      EXPECT_NEAR(p.x, cx + r * std::sin(h), 1e-9) << "k=" << k << " ds=" << ds;
      EXPECT_NEAR(p.y, cy - r * std::cos(h), 1e-9);
      EXPECT_NEAR(p.heading, h, 1e-12);
    }
  }
}

TEST(OpenDriveGeometry, SpiralMatchesAFineMidpointIntegration) {
  const double k0 = -0.002;
  const double k1 = 0.01;
  const double length = 150.0;
  const Geometry g = at(3.0, 4.0, 1.1, length, Spiral{k0, k1});
  // Independent reference: 300,000 midpoint steps of (cos, sin) of the heading.
  const double ds_end = 120.0;
  const int steps = 300000;
  const double h = ds_end / steps;
  double x = 3.0;
  double y = 4.0;
  for (int i = 0; i < steps; ++i) {
    const double s = (i + 0.5) * h;
    const double heading = 1.1 + k0 * s + 0.5 * (k1 - k0) / length * s * s;
    x += h * std::cos(heading);
    y += h * std::sin(heading);
  }
  const Pose2 p = evaluate(g, ds_end);
  EXPECT_NEAR(p.x, x, 1e-6);
  EXPECT_NEAR(p.y, y, 1e-6);
  EXPECT_NEAR(p.heading, 1.1 + k0 * ds_end + 0.5 * (k1 - k0) / length * ds_end * ds_end, 1e-12);
  EXPECT_NEAR(curvature(g, 75.0), k0 + (k1 - k0) * 0.5, 1e-12);
}

TEST(OpenDriveGeometry, Poly3WithSlopeOnlyIsAStraightLineMeasuredByArcLength) {
  // v = 1 + 0.5 u: a line at atan(0.5), offset 1 m to the left; s is arc length.
  const Geometry g = at(0.0, 0.0, 0.0, 50.0, Poly3{1.0, 0.5, 0.0, 0.0});
  const double ds = 20.0;
  const double u = ds / std::sqrt(1.0 + 0.25);
  const Pose2 p = evaluate(g, ds);
  EXPECT_NEAR(p.x, u, 1e-9);
  EXPECT_NEAR(p.y, 1.0 + 0.5 * u, 1e-9);
  EXPECT_NEAR(p.heading, std::atan(0.5), 1e-12);
}

TEST(OpenDriveGeometry, Poly3ParabolaPointLiesOnTheCurveAtTheRightArcLength) {
  const Poly3 poly{0.0, 0.0, 0.01, 0.0};
  const Geometry g = at(0.0, 0.0, 0.0, 60.0, poly);
  const Pose2 p = evaluate(g, 40.0);
  EXPECT_NEAR(p.y, 0.01 * p.x * p.x, 1e-9);
  // Closed-form arc length of y = c x^2 from 0 to x.
  const double a = 2 * 0.01 * p.x;
  const double arc = (a * std::sqrt(1 + a * a) + std::asinh(a)) / (4 * 0.01);
  EXPECT_NEAR(arc, 40.0, 1e-8);
  EXPECT_NEAR(p.heading, std::atan(2 * 0.01 * p.x), 1e-12);
}

TEST(OpenDriveGeometry, ParamPoly3NormalizedAndArcLengthRanges) {
  // A straight line of 30 m along 45 degrees written as u(p) = 30 p (normalized).
  const Geometry normalized = at(0.0, 0.0, std::numbers::pi / 4, 30.0, ParamPoly3{0, 30, 0, 0, 0, 0, 0, 0, true});
  const Pose2 p = evaluate(normalized, 15.0);
  EXPECT_NEAR(p.x, 15.0 * std::cos(std::numbers::pi / 4), 1e-12);
  EXPECT_NEAR(p.y, 15.0 * std::sin(std::numbers::pi / 4), 1e-12);
  // arcLength range: p runs 0..length; u = p, v = 0: a line of 30 m.
  const Geometry arc_length = at(0.0, 0.0, 0.0, 30.0, ParamPoly3{0, 1, 0, 0, 0, 0, 0, 0, false});
  const Pose2 q = evaluate(arc_length, 10.0);
  EXPECT_NEAR(q.x, 10.0, 1e-12);
  EXPECT_NEAR(q.y, 0.0, 1e-12);
}

// The length of a curve between two values of s, by a fine chord sum (independent of the
// evaluator's quadrature).
double chord_length(const Geometry& g, double from, double to) {
  double sum = 0.0;
  Pose2 last = evaluate(g, from);
  for (int i = 1; i <= 2000; ++i) {
    const Pose2 next = evaluate(g, from + (to - from) * i / 2000.0);
    sum += std::hypot(next.x - last.x, next.y - last.y);
    last = next;
  }
  return sum;
}

// s is the length along the reference line, also on a parametric cubic whose parameter does
// not run at a constant speed: SUMO's right turn of junction_route.xosc (road 50,
// u = 14.4 p - 7.2 p^2, v = -7.2 p^2, normalized; the curve runs 1.23 times faster than p at
// its start, 0.87 times at its middle), and the same curve with a length attribute 10 %
// short of the curve's (scaled, as esmini does: s still ends at the curve's end). With p
// proportional to s the first half metre is 0.62 m of curve.
TEST(OpenDriveGeometry, ParamPoly3AdvancesAlongItsArcLength) {
  const ParamPoly3 turn{0, 14.4, -7.2, 0, 0, 0, -7.2, 0, true};
  const double length = 11.67729721;
  const Geometry g = at(-7.2, 0.0, 0.0, length, turn);
  // The file's length is 0.08 % short of the curve's (11.6872 m): every metre of s is the
  // same stretch of curve, the curve's length over the record's.
  const double total = chord_length(g, 0.0, length);
  EXPECT_NEAR(total, 11.6872, 1e-4);
  for (double ds = 0.0; ds + 0.5 <= length; ds += 0.5)
    EXPECT_NEAR(chord_length(g, ds, ds + 0.5), 0.5 * total / length, 1e-6) << "ds=" << ds;
  const Pose2 end = evaluate(g, length);
  EXPECT_NEAR(end.x, 0.0, 1e-12);
  EXPECT_NEAR(end.y, -7.2, 1e-12);
  EXPECT_NEAR(end.heading, -std::numbers::pi / 2, 1e-12);
  // Curvature at s: the turn of the heading over a short stretch of s (per metre of s, as
  // the entity's motion uses it).
  for (const double ds : {0.5, 3.0, 5.8, 9.0}) {
    const double turned = evaluate(g, ds + 1e-4).heading - evaluate(g, ds - 1e-4).heading;
    EXPECT_NEAR(curvature(g, ds), turned / 2e-4, 1e-6) << "ds=" << ds;
  }
  const Geometry short_length = at(-7.2, 0.0, 0.0, 0.9 * length, turn);
  for (double ds = 0.0; ds + 0.5 <= 0.9 * length; ds += 0.5)
    EXPECT_NEAR(chord_length(short_length, ds, ds + 0.5), 0.5 * total / (0.9 * length), 1e-6) << "ds=" << ds;
  EXPECT_NEAR(evaluate(short_length, 0.9 * length).y, -7.2, 1e-12);
  // arcLength range: u = p, v = 0.001 p^3 over p in [0, 30] (37.1 m of curve, length 30).
  const Geometry cubic = at(0.0, 0.0, 0.0, 30.0, ParamPoly3{0, 1, 0, 0, 0, 0, 0, 0.001, false});
  const double cubic_total = chord_length(cubic, 0.0, 30.0);
  for (double ds = 0.0; ds + 1.0 <= 30.0; ds += 1.0)
    EXPECT_NEAR(chord_length(cubic, ds, ds + 1.0), cubic_total / 30.0, 1e-6) << "ds=" << ds;
  EXPECT_NEAR(evaluate(cubic, 30.0).y, 27.0, 1e-12);
}

const char* kTwoSectionRoad = R"(<?xml version="1.0"?>
<OpenDRIVE>
  <header revMajor="1" revMinor="6"/>
  <road id="7" length="200" junction="-1">
    <type s="0" type="motorway"><speed max="120" unit="km/h"/></type>
    <planView>
      <geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry>
      <geometry s="100" x="100" y="0" hdg="0" length="100"><arc curvature="0.01"/></geometry>
    </planView>
    <lanes>
      <laneOffset s="0" a="0.5" b="0" c="0" d="0"/>
      <laneOffset s="150" a="0.5" b="0.01" c="0" d="0"/>
      <laneSection s="0">
        <left><lane id="1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></left>
        <center><lane id="0" type="none"/></center>
        <right>
          <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
          <lane id="-2" type="stop"><width sOffset="0" a="2" b="0.01" c="0" d="0"/>
            <speed sOffset="0" max="10" unit="m/s"/></lane>
        </right>
      </laneSection>
      <laneSection s="120">
        <right><lane id="-1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/>
          <width sOffset="20" a="3" b="0" c="0.001" d="0"/></lane></right>
      </laneSection>
    </lanes>
  </road>
</OpenDRIVE>)";

TEST(OpenDriveLanes, LaneCentresSumOffsetAndWidthPolynomials) {
  const RoadNetwork net = read_xodr_text(kTwoSectionRoad, "two_sections.xodr");
  const Road& road = net.road("7");
  ASSERT_TRUE(road.type_speed_mps.has_value());
  EXPECT_NEAR(*road.type_speed_mps, 120 / 3.6, 1e-12);
  // s = 50: offset 0.5; lane -1 spans [0.5, -3], lane -2 is 2 + 0.01 * 50 = 2.5 wide.
  EXPECT_NEAR(road.lane_center_t(1, 50.0), 0.5 + 1.5, 1e-12);
  EXPECT_NEAR(road.lane_center_t(-1, 50.0), 0.5 - 1.75, 1e-12);
  EXPECT_NEAR(road.lane_center_t(-2, 50.0), 0.5 - 3.5 - 1.25, 1e-12);
  EXPECT_EQ(road.lane_at(50.0, -4.0), -2);
  EXPECT_EQ(road.lane_at(50.0, 2.0), 1);
  EXPECT_FALSE(road.lane_at(50.0, 9.0).has_value());
  // Second section at s = 160: offset 0.5 + 0.01 * 10; width 3 + 0.001 * 20^2 (sOffset 20).
  const double offset = 0.5 + 0.01 * 10;
  const double width = 3.0 + 0.001 * 20 * 20;
  EXPECT_NEAR(road.lane_center_t(-1, 160.0), offset - width / 2, 1e-12);
  EXPECT_THROW((void)road.lane_center_t(-2, 160.0), MapError);
  // On the arc (s = 150, second section, 30 m in): lane -1 is 3 + 0.001 * 10^2 wide, the
  // offset 0.5; the point lies t metres to the left of the reference point.
  const Pose2 p = net.lane_pose("7", -1, 150.0, 0.25);
  const double h = 0.01 * 50;
  const double t = 0.5 - (3.0 + 0.001 * 10 * 10) / 2 + 0.25;
  EXPECT_NEAR(p.x, 100 + 100 * std::sin(h) - t * std::sin(h), 1e-9);
  EXPECT_NEAR(p.y, 100 * (1 - std::cos(h)) + t * std::cos(h), 1e-9);
  EXPECT_NEAR(p.heading, h, 1e-12);
}

TEST(OpenDriveLanes, WorldToRoadInvertsRoadToWorld) {
  const RoadNetwork net = read_xodr_text(kTwoSectionRoad, "two_sections.xodr");
  for (const double s : {3.0, 99.0, 100.5, 140.0, 190.0}) {
    for (const double t : {-3.0, 1.0}) {
      const Pose2 p = net.road("7").world(s, t);
      const auto back = net.to_road(p.x, p.y);
      ASSERT_TRUE(back.has_value());
      EXPECT_EQ(back->road_id, "7");
      EXPECT_NEAR(back->s, s, 1e-7) << s << " " << t;
      EXPECT_NEAR(back->t, t, 1e-7);
    }
  }
}

TEST(OpenDriveReader, UnknownGeometryIsAnErrorWithLineAndSuggestion) {
  std::string text = kTwoSectionRoad;
  text.replace(text.find("<line/>"), 7, "<lnie/>");
  try {
    (void)read_xodr_text(text, "bad.xodr");
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bad.xodr:7"), std::string::npos) << message;
    EXPECT_NE(message.find("/OpenDRIVE/road/planView/geometry[1]/lnie"), std::string::npos) << message;
    EXPECT_NE(message.find("did you mean \"line\""), std::string::npos) << message;
  }
}

TEST(OpenDriveReader, BadNumberNamesTheAttribute) {
  std::string text = kTwoSectionRoad;
  text.replace(text.find("curvature=\"0.01\""), 16, "curvature=\"0.0x\"");
  try {
    (void)read_xodr_text(text, "bad.xodr");
    FAIL() << "expected an error";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("arc/@curvature: expected a number, found \"0.0x\""), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace orch::opendrive
