// OpenDRIVE -> SUMO net with the real netconvert: lane types, speeds, the content cache and
// byte-identical output.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "opendrive/sumo_net.hpp"
#include "support/cli_runner.hpp"

namespace {

using namespace orch::opendrive;
using orch::test::TempDir;

const char* kRoad = R"(<?xml version="1.0"?>
<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="400" junction="-1"><type s="0" type="motorway"/>
 <planView>
  <geometry s="0" x="0" y="0" hdg="0" length="200"><line/></geometry>
  <geometry s="200" x="200" y="0" hdg="0" length="200"><arc curvature="-0.004"/></geometry>
 </planView>
 <lanes><laneSection s="0">
  <left>
   <lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
  </left>
  <center><lane id="0" type="none"/></center>
  <right>
   <lane id="-1" type="border"><width sOffset="0" a="0.5" b="0" c="0" d="0"/></lane>
   <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
   <lane id="-3" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/><speed sOffset="0" max="80" unit="km/h"/></lane>
   <lane id="-4" type="stop"><width sOffset="0" a="3.0" b="0" c="0" d="0"/></lane>
  </right>
 </laneSection></lanes>
</road></OpenDRIVE>)";

struct NetLane {
  std::string allow, disallow;
  double speed = 0;
};

std::vector<NetLane> lanes_of(const std::filesystem::path& net, const std::string& edge) {
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(net.c_str()));
  std::vector<NetLane> out;
  for (const pugi::xml_node lane : doc.child("net").find_child_by_attribute("edge", "id", edge.c_str()).children("lane"))
    out.push_back({lane.attribute("allow").value(), lane.attribute("disallow").value(), lane.attribute("speed").as_double()});
  return out;
}

TEST(OpenDriveSumoNet, ConvertsWithLaneTypesAndSpeeds) {
  TempDir dir;
  const auto road = dir.write("road.xodr", kRoad);
  const SumoNet net = convert_to_sumo_net(road, dir / "cache");
  EXPECT_FALSE(net.from_cache);
  // Right side, SUMO lane index 0 = outermost: stop (shoulder), lane -3 (80 km/h), lane -2.
  const auto right = lanes_of(net.net_file, "-0");
  ASSERT_EQ(right.size(), 3u);  // the border lane is discarded
  EXPECT_EQ(right[0].allow, "authority");
  EXPECT_NEAR(right[1].speed, 80 / 3.6, 0.01);
  EXPECT_NEAR(right[2].speed, 130 / 3.6, 0.01);  // motorway default, not netconvert's 13.89
  EXPECT_NE(right[2].disallow.find("pedestrian"), std::string::npos);
  const auto left = lanes_of(net.net_file, "0");
  ASSERT_EQ(left.size(), 1u);
  EXPECT_NEAR(left[0].speed, 130 / 3.6, 0.01);
}

TEST(OpenDriveSumoNet, CachedPerContentAndByteIdentical) {
  TempDir dir;
  const auto road = dir.write("road.xodr", kRoad);
  const SumoNet first = convert_to_sumo_net(road, dir / "cache_a");
  const SumoNet again = convert_to_sumo_net(road, dir / "cache_a");
  EXPECT_TRUE(again.from_cache);
  EXPECT_EQ(again.net_file, first.net_file);
  // A fresh conversion elsewhere (same content, other file name) gives the same bytes.
  std::filesystem::create_directories(dir / "elsewhere");
  const auto copy = dir.write("elsewhere/other_name.xodr", kRoad);
  const SumoNet fresh = convert_to_sumo_net(copy, dir / "cache_b");
  EXPECT_FALSE(fresh.from_cache);
  EXPECT_EQ(fresh.key, first.key);
  EXPECT_EQ(orch::read_file(fresh.net_file), orch::read_file(first.net_file));
  EXPECT_EQ(orch::read_file(first.net_file).find("generated on"), std::string::npos);
  // Other content, other entry.
  std::string changed = kRoad;
  changed.replace(changed.find("max=\"80\""), 8, "max=\"90\"");
  EXPECT_NE(convert_to_sumo_net(dir.write("changed.xodr", changed), dir / "cache_a").key, first.key);
}

// netconvert copies a road's geoReference into the net's projection, which SUMO would turn
// into a PROJ transformation on every load; the cached net carries none, and the same lanes.
TEST(OpenDriveSumoNet, TheNetCarriesNoProjection) {
  TempDir dir;
  std::string geo = kRoad;
  const std::string header = "<header revMajor=\"1\" revMinor=\"6\"/>";
  geo.replace(geo.find(header), header.size(),
              "<header revMajor=\"1\" revMinor=\"6\"><geoReference><![CDATA[+proj=utm +zone=32 +ellps=WGS84 "
              "+units=m +no_defs]]></geoReference></header>");
  const SumoNet with_geo = convert_to_sumo_net(dir.write("geo.xodr", geo), dir / "cache");
  const SumoNet plain = convert_to_sumo_net(dir.write("road.xodr", kRoad), dir / "cache");
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(with_geo.net_file.c_str()));
  EXPECT_STREQ(doc.child("net").child("location").attribute("projParameter").value(), "!");
  EXPECT_EQ(orch::read_file(with_geo.net_file).find("+proj"), std::string::npos);
  for (const std::string edge : {"-0", "0"}) {
    const auto a = lanes_of(with_geo.net_file, edge), b = lanes_of(plain.net_file, edge);
    ASSERT_EQ(a.size(), b.size()) << edge;
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].speed, b[i].speed) << edge << " " << i;
  }
}

TEST(OpenDriveSumoNet, BrokenFileIsAnErrorNamingItAndLeavesNoCacheEntry) {
  TempDir dir;
  const auto road = dir.write("broken.xodr", std::string(kRoad).substr(0, 300));
  try {
    (void)convert_to_sumo_net(road, dir / "cache");
    FAIL() << "expected an error";
  } catch (const orch::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.xodr"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(!std::filesystem::exists(dir / "cache") || std::filesystem::is_empty(dir / "cache"));
}

}  // namespace
