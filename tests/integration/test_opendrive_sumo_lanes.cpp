// Each OpenDRIVE lane's SUMO lane, on nets the real netconvert made: the lane found runs
// through the OpenDRIVE lane's centre (one lane section and two, border lanes dropped).
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include <cmath>
#include <limits>

#include "opendrive/sumo_lanes.hpp"
#include "opendrive/sumo_net.hpp"
#include "opendrive/xodr_reader.hpp"
#include "support/cli_runner.hpp"

namespace {

using namespace orch::opendrive;
using orch::test::TempDir;

// Two lane sections: the right side narrows from three lanes to two at s = 150.
const char* kRoad = R"(<?xml version="1.0"?>
<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="7" length="300" junction="-1"><type s="0" type="motorway"/>
 <planView>
  <geometry s="0" x="10" y="20" hdg="0.3" length="100"><line/></geometry>
  <geometry s="100" x="105.5336489" y="49.5520206" hdg="0.3" length="200"><arc curvature="0.002"/></geometry>
 </planView>
 <lanes>
 <laneSection s="0">
  <left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
  <center><lane id="0" type="none"/></center>
  <right>
   <lane id="-1" type="border"><width sOffset="0" a="0.5" b="0" c="0" d="0"/></lane>
   <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
   <lane id="-3" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
   <lane id="-4" type="stop"><width sOffset="0" a="3.0" b="0" c="0" d="0"/></lane>
  </right>
 </laneSection>
 <laneSection s="150">
  <left><lane id="1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
  <center><lane id="0" type="none"/></center>
  <right>
   <lane id="-1" type="border"><width sOffset="0" a="0.5" b="0" c="0" d="0"/></lane>
   <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
   <lane id="-3" type="stop"><width sOffset="0" a="3.0" b="0" c="0" d="0"/></lane>
  </right>
 </laneSection>
 </lanes>
</road></OpenDRIVE>)";

// Distance from (x, y) to the shape of SUMO lane `lane_id` in `net`.
double distance_to_lane(const pugi::xml_document& net, const std::string& lane_id, double x, double y) {
  const pugi::xml_node lane = net.select_node(("/net/edge/lane[@id='" + lane_id + "']").c_str()).node();
  if (!lane) return std::numeric_limits<double>::infinity();
  std::vector<std::pair<double, double>> pts;
  std::istringstream shape(lane.attribute("shape").value());
  std::string pair;
  while (shape >> pair) {
    const auto comma = pair.find(',');
    pts.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const auto [ax, ay] = pts[i - 1];
    const double dx = pts[i].first - ax, dy = pts[i].second - ay;
    const double u = std::clamp(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    best = std::min(best, std::hypot(ax + u * dx - x, ay + u * dy - y));
  }
  return best;
}

TEST(OpenDriveSumoLanes, EveryKeptLaneMapsToTheSumoLaneThroughItsCentre) {
  TempDir dir;
  const auto road_file = dir.write("road.xodr", kRoad);
  const RoadNetwork roads = read_xodr_file(road_file.string());
  const SumoNet net = convert_to_sumo_net(road_file, dir / "cache");
  const SumoLaneIndex index(roads, net.net_file.string());
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(net.net_file.c_str()));
  std::string edges;  // for failure messages
  for (const pugi::xml_node e : doc.child("net").children("edge"))
    edges += std::string(" ") + e.attribute("id").value() + "(" +
             std::to_string(std::distance(e.children("lane").begin(), e.children("lane").end())) + ")";
  struct Case { int lane; double s; };
  for (const Case c : {Case{-2, 20}, Case{-3, 60}, Case{-4, 100}, Case{1, 30}, Case{1, 200}, Case{-2, 180},
                       Case{-3, 280}}) {
    const auto found = index.find("7", c.lane, c.s);
    ASSERT_TRUE(found.has_value()) << "lane " << c.lane << " s " << c.s << "; edges:" << edges;
    const Pose2 centre = roads.lane_pose("7", c.lane, c.s, 0.0);
    const std::string sumo_lane = found->edge + "_" + std::to_string(found->index);
    EXPECT_LT(distance_to_lane(doc, sumo_lane, centre.x, centre.y), 0.05)
        << "lane " << c.lane << " s " << c.s << " -> " << sumo_lane;
  }
  // Border lanes, the centre lane, unknown roads and lanes: no SUMO lane.
  EXPECT_FALSE(index.find("7", -1, 20).has_value());
  EXPECT_FALSE(index.find("7", 0, 20).has_value());
  EXPECT_FALSE(index.find("8", -2, 20).has_value());
  EXPECT_FALSE(index.find("7", -4, 200).has_value());
}

}  // namespace
