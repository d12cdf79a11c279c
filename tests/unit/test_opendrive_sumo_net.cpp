// The pure parts of the OpenDRIVE -> SUMO conversion: lane speeds and the lane type map.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include "opendrive/sumo_net.hpp"
#include "opendrive/xodr_reader.hpp"

namespace orch::opendrive {
namespace {

const char* kRoads = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="1" length="50" junction="-1"><type s="0" type="motorway"/>
 <planView><geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><right>
  <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
  <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><speed sOffset="0" max="20" unit="m/s"/></lane>
  <lane id="-3" type="stop"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane>
 </right></laneSection></lanes></road>
<road id="2" length="50" junction="-1"><type s="0" type="town"><speed max="40" unit="km/h"/></type>
 <planView><geometry s="0" x="0" y="10" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><left><lane id="1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></left></laneSection></lanes></road>
<road id="3" length="50" junction="-1">
 <planView><geometry s="0" x="0" y="20" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><left><lane id="1" type="driving"><width sOffset="0" a="3" b="0" c="0" d="0"/></lane></left></laneSection></lanes></road>
</OpenDRIVE>)";

TEST(OpenDriveSumoNet, LanesWithoutSpeedGetTheirRoadsSpeed) {
  const RoadNetwork net = read_xodr_text(with_lane_speeds(kRoads, "roads.xodr"), "converted.xodr");
  const auto speed_of = [&](const std::string& road, int lane) {
    const Lane* l = net.road(road).sections.front().lane(lane);
    return l->speeds.empty() ? -1.0 : l->speeds.front().max_mps;
  };
  EXPECT_NEAR(speed_of("1", -1), 130 / 3.6, 1e-4);  // motorway default
  EXPECT_NEAR(speed_of("1", -2), 20.0, 1e-12);      // its own record is kept
  EXPECT_EQ(speed_of("1", -3), -1.0);               // the hard shoulder carries no traffic
  EXPECT_NEAR(speed_of("2", 1), 40 / 3.6, 1e-4);    // the road type's own speed record
  EXPECT_NEAR(speed_of("3", 1), 100 / 3.6, 1e-4);   // no road type: rural default
}

// Shoulders are for scripted entities only; sidewalks and cycle lanes take them besides SUMO's
// own pedestrians and bicycles (a pedestrian entity placed on a sidewalk is a SUMO vehicle of
// the class "authority": SUMO refused to insert it before).
TEST(OpenDriveSumoNet, LaneTypeMapKeepsShouldersForScriptedEntitiesOnly) {
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(lane_type_map_xml().c_str()));
  const auto type = [&](const char* id) { return doc.child("types").find_child_by_attribute("type", "id", id); };
  EXPECT_STREQ(type("stop").attribute("allow").value(), "authority");
  EXPECT_FALSE(type("stop").attribute("discard"));
  EXPECT_STREQ(type("shoulder").attribute("allow").value(), "authority");
  EXPECT_STREQ(type("sidewalk").attribute("allow").value(), "pedestrian authority");
  EXPECT_STREQ(type("biking").attribute("allow").value(), "bicycle authority");
  EXPECT_STREQ(type("border").attribute("discard").value(), "true");
  EXPECT_NE(std::string(type("driving").attribute("disallow").value()).find("pedestrian"), std::string::npos);
}

}  // namespace
}  // namespace orch::opendrive
