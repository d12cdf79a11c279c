// OpenDRIVE content netconvert 1.15 refuses, rewritten in the copy it reads (with a warning
// naming the line): signals without a type, direct junctions.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include "opendrive/sumo_net.hpp"

namespace orch::opendrive {
namespace {

const char* kRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="7"/>
<road id="0" length="50" junction="-1">
 <link><predecessor elementType="junction" elementId="8"/></link>
 <planView><geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
  <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>
 <signals>
  <signal s="10" t="-3" id="1" type="" country="" subtype=""/>
  <signal s="20" t="-3" id="2" type="274" country="de" subtype=""/>
 </signals>
</road>
<road id="2" length="50" junction="-1">
 <link><successor elementType="junction" elementId="8"/></link>
 <planView><geometry s="0" x="-50" y="0" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>
</road>
<road id="5" length="50" junction="-1">
 <link><successor elementType="junction" elementId="8"/></link>
 <planView><geometry s="0" x="-50" y="-3.5" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>
</road>
<junction name="" id="8" type="direct">
 <connection id="0" incomingRoad="2" linkedRoad="0" contactPoint="start"><laneLink from="-1" to="-1"/></connection>
 <connection id="1" incomingRoad="5" linkedRoad="0" contactPoint="start"><laneLink from="-1" to="-2"/></connection>
</junction>
</OpenDRIVE>)";

pugi::xml_node road(const pugi::xml_document& doc, const char* id) {
  return doc.child("OpenDRIVE").find_child_by_attribute("road", "id", id);
}

TEST(NetconvertWorkarounds, SignalWithoutTypeIsDroppedWithAWarningNamingItsLine) {
  const NetconvertInput input = netconvert_input(kRoad, "merge.xodr");
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(input.text.c_str()));
  const pugi::xml_node signals = road(doc, "0").child("signals");
  EXPECT_FALSE(signals.find_child_by_attribute("signal", "id", "1"));
  EXPECT_TRUE(signals.find_child_by_attribute("signal", "id", "2"));  // a typed signal stays
  ASSERT_EQ(input.warnings.size(), 2u);
  EXPECT_EQ(input.warnings[0].where.file, "merge.xodr");
  EXPECT_EQ(input.warnings[0].where.line, 8);
  EXPECT_NE(input.warnings[0].message.find("signal 1 of road 0 has no type"), std::string::npos);
}

TEST(NetconvertWorkarounds, DirectJunctionBecomesRoadLinks) {
  const NetconvertInput input = netconvert_input(kRoad, "merge.xodr");
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(input.text.c_str()));
  EXPECT_FALSE(doc.child("OpenDRIVE").child("junction"));
  const pugi::xml_node before = road(doc, "0").child("link").child("predecessor");
  EXPECT_STREQ(before.attribute("elementType").value(), "road");
  EXPECT_STREQ(before.attribute("elementId").value(), "2");  // the first connection's incoming road
  EXPECT_STREQ(before.attribute("contactPoint").value(), "end");
  for (const char* incoming : {"2", "5"}) {
    const pugi::xml_node after = road(doc, incoming).child("link").child("successor");
    EXPECT_STREQ(after.attribute("elementType").value(), "road") << incoming;
    EXPECT_STREQ(after.attribute("elementId").value(), "0") << incoming;
    EXPECT_STREQ(after.attribute("contactPoint").value(), "start") << incoming;
  }
  ASSERT_EQ(input.warnings.size(), 2u);
  EXPECT_EQ(input.warnings[1].where.line, 22);
  EXPECT_NE(input.warnings[1].message.find("direct junction 8"), std::string::npos);
}

TEST(NetconvertWorkarounds, StandardContentIsLeftAsItIs) {
  const char* plain = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="1" length="50" junction="-1">
 <planView><geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry></planView>
 <lanes><laneSection s="0"><right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>
 <signals><signal s="20" t="-3" id="2" type="274" country="de" subtype=""/></signals>
</road></OpenDRIVE>)";
  const NetconvertInput input = netconvert_input(plain, "plain.xodr");
  EXPECT_TRUE(input.warnings.empty());
  EXPECT_EQ(input.text, with_lane_speeds(plain, "plain.xodr"));
}

}  // namespace
}  // namespace orch::opendrive
