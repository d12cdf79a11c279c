#pragma once
// Small OpenDRIVE networks written by hand for tests of links, junctions and routes: roads
// are lines or arcs with one lane each side (3.5 m; lane -1 drives along s, lane 1 against).
#include <numbers>
#include <string>

#include <fmt/format.h>

namespace orch::test {

// <link> of a road: each of pred / succ is "" (none), "road ID start|end" or "junction ID".
inline std::string xodr_road_link(const std::string& end, const std::string& spec) {
  if (spec.empty()) return "";
  const auto space = spec.find(' ');
  const std::string kind = spec.substr(0, space);
  std::string rest = spec.substr(space + 1);
  if (kind == "junction") return fmt::format("<{} elementType=\"junction\" elementId=\"{}\"/>", end, rest);
  const auto second = rest.find(' ');
  return fmt::format("<{} elementType=\"road\" elementId=\"{}\" contactPoint=\"{}\"/>", end, rest.substr(0, second),
                     rest.substr(second + 1));
}

struct XodrRoad {
  std::string id;
  double x = 0, y = 0, hdg = 0, length = 100;
  std::string pred, succ;           // see xodr_road_link
  std::string junction = "-1";
  double curvature = 0;             // 0: a line
  std::string right_links = "<predecessor id=\"-1\"/><successor id=\"-1\"/>";  // lane -1's <link> content
  std::string left_links = "<predecessor id=\"1\"/><successor id=\"1\"/>";     // lane 1's
  double right_speed = 0;           // m/s speed record of lane -1 (0: none)
};

inline std::string xodr_road(const XodrRoad& r) {
  const std::string shape = r.curvature == 0 ? "<line/>" : fmt::format("<arc curvature=\"{}\"/>", r.curvature);
  const std::string speed = r.right_speed > 0 ? fmt::format("<speed sOffset=\"0\" max=\"{}\" unit=\"m/s\"/>", r.right_speed) : "";
  return fmt::format(
      R"(<road id="{}" length="{}" junction="{}"><link>{}{}</link>
<planView><geometry s="0" x="{}" y="{}" hdg="{}" length="{}">{}</geometry></planView>
<lanes><laneSection s="0">
<left><lane id="1" type="driving"><link>{}</link><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
<center><lane id="0" type="none"/></center>
<right><lane id="-1" type="driving"><link>{}</link><width sOffset="0" a="3.5" b="0" c="0" d="0"/>{}</lane></right>
</laneSection></lanes></road>
)",
      r.id, r.length, r.junction, xodr_road_link("predecessor", r.pred), xodr_road_link("successor", r.succ), r.x, r.y,
      r.hdg, r.length, shape, r.left_links, r.right_links, speed);
}

// A <connection> of a junction: incoming road, connecting road, contact point, lane links "from:to,...".
inline std::string xodr_connection(const std::string& id, const std::string& incoming, const std::string& connecting,
                                   const std::string& contact, const std::string& lane_links = "-1:-1") {
  std::string links;
  std::size_t at = 0;
  while (at < lane_links.size()) {
    const auto comma = lane_links.find(',', at);
    const std::string pair = lane_links.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    const auto colon = pair.find(':');
    links += fmt::format("<laneLink from=\"{}\" to=\"{}\"/>", pair.substr(0, colon), pair.substr(colon + 1));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return fmt::format(R"(<connection id="{}" incomingRoad="{}" connectingRoad="{}" contactPoint="{}">{}</connection>)",
                     id, incoming, connecting, contact, links);
}

inline std::string xodr_file(const std::string& body) {
  return R"(<?xml version="1.0"?><OpenDRIVE><header revMajor="1" revMinor="6"/>)" + body + "</OpenDRIVE>";
}

// Road 1 then road 2 along +x (100 m, 50 m).
inline std::string xodr_two_in_a_row() {
  return xodr_file(xodr_road({"1", 0, 0, 0, 100, "", "road 2 start"}) + xodr_road({"2", 100, 0, 0, 50, "road 1 end", ""}));
}

// Road 1 along +x meets the END of road 3, which points back (heading pi): lane -1 of road 1
// continues on lane 1 of road 3, driving against road 3's s.
inline std::string xodr_contact_end() {
  XodrRoad one{"1", 0, 0, 0, 100, "", "road 3 end"};
  one.right_links = R"(<successor id="1"/>)";
  one.left_links = R"(<successor id="-1"/>)";
  XodrRoad three{"3", 150, 0, std::numbers::pi, 50, "", "road 1 end"};
  three.left_links = R"(<successor id="-1"/>)";
  three.right_links = R"(<successor id="1"/>)";
  return xodr_file(xodr_road(one) + xodr_road(three));
}

// Road 1 (+x, 100 m) ends at junction J: connecting road 11 turns left (arc of radius 10)
// onto road 3 (+y from (110, 10)), connecting road 10 goes straight on (20 m) onto road 2
// (from (120, 0)). Road 2's lane 1 comes back on 10.
inline std::string xodr_three_way() {
  const double quarter = std::numbers::pi / 2 * 10;
  XodrRoad c10{"10", 100, 0, 0, 20, "road 1 end", "road 2 start", "J"};
  XodrRoad c11{"11", 100, 0, 0, quarter, "road 1 end", "road 3 start", "J", 0.1};
  const std::string junction = "<junction id=\"J\">" + xodr_connection("0", "1", "11", "start") +
                               xodr_connection("1", "1", "10", "start") +
                               xodr_connection("2", "2", "10", "end", "1:1") + "</junction>";
  return xodr_file(xodr_road({"1", 0, 0, 0, 100, "", "junction J"}) + xodr_road({"2", 120, 0, 0, 100, "junction J", ""}) +
                   xodr_road({"3", 110, 10, std::numbers::pi / 2, 100, "junction J", ""}) + xodr_road(c10) +
                   xodr_road(c11) + junction);
}

}  // namespace orch::test
