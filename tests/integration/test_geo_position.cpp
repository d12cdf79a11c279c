// GeoPosition against an independent reference: SUMO's own geo conversion of the same road.
// netconvert keeps an OpenDRIVE road's geoReference as the net's projection and moves the
// road by the net's offset; libsumo's Simulation::convertGeo then turns longitude and latitude
// into net coordinates. The orchestrator's projection (opendrive/geo_projection.hpp) must give
// the same road point, the net offset taken off.
#include <gtest/gtest.h>
#include <libsumo/libsumo.h>

#include <pugixml.hpp>

#include "core/process.hpp"
#include "opendrive/geo_projection.hpp"
#include "opendrive/xodr_reader.hpp"
#include "support/cli_runner.hpp"

namespace orch {
namespace {

// A curved road (line, arc) far from the projection's origin, in a UTM zone's bare PROJ
// string as road editors write it.
const char* kRoad = R"(<?xml version="1.0"?>
<OpenDRIVE><header revMajor="1" revMinor="6">
<geoReference><![CDATA[+proj=utm +zone=32 +ellps=WGS84 +datum=WGS84 +units=m +no_defs]]></geoReference></header>
<road id="0" length="400" junction="-1">
 <planView>
  <geometry s="0" x="691000" y="5334000" hdg="0.3" length="200"><line/></geometry>
  <geometry s="200" x="691191.067" y="5334059.104" hdg="0.3" length="200"><arc curvature="0.004"/></geometry>
 </planView>
 <lanes><laneSection s="0"><right>
  <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 </right></laneSection></lanes>
</road></OpenDRIVE>)";

TEST(GeoPositionAgainstSumo, TheProjectionGivesTheRoadPointSumoGives) {
  test::TempDir dir;
  const auto road = dir.write("road.xodr", kRoad);
  const auto net = dir / "road.net.xml";
  const ProcessResult converted =
      run_process("netconvert", {"--opendrive-files", road.string(), "-o", net.string(), "--no-warnings"});
  ASSERT_EQ(converted.exit_code, 0) << converted.output;
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(net.c_str()));
  const pugi::xml_node location = doc.child("net").child("location");
  ASSERT_NE(std::string(location.attribute("projParameter").value()), "!");
  double offset_x = 0, offset_y = 0;
  ASSERT_EQ(std::sscanf(location.attribute("netOffset").value(), "%lf,%lf", &offset_x, &offset_y), 2);

  const opendrive::RoadNetwork roads = opendrive::read_xodr_file(road.string());
  const opendrive::GeoProjection projection(roads.geo_reference());
  libsumo::Simulation::start({"sumo", "-n", net.string(), "--no-step-log", "--no-warnings"});
  int compared = 0;
  for (double s = 0; s <= 400; s += 50) {
    for (const double t : {0.0, -1.75, -3.5}) {
      const opendrive::Pose2 point = roads.road("0").world(s, t);
      const opendrive::GeoPoint geo = projection.geographic(Vec2{point.x, point.y});
      const libsumo::TraCIPosition sumo = libsumo::Simulation::convertGeo(geo.longitude_deg, geo.latitude_deg, true);
      EXPECT_NEAR(sumo.x - offset_x, point.x, 0.01) << "s " << s << " t " << t;
      EXPECT_NEAR(sumo.y - offset_y, point.y, 0.01) << "s " << s << " t " << t;
      const Vec2 ours = projection.local(geo);
      EXPECT_NEAR(ours.x(), point.x, 1e-6);
      EXPECT_NEAR(ours.y(), point.y, 1e-6);
      ++compared;
    }
  }
  libsumo::Simulation::close();
  EXPECT_EQ(compared, 27);
}

}  // namespace
}  // namespace orch
