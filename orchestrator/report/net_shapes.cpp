#include "report/net_shapes.hpp"

#include <fmt/format.h>

#include <charconv>
#include <pugixml.hpp>

#include "core/errors.hpp"

namespace orch::report {

namespace {

// SUMO's shape attribute: "x,y x,y ..." (a z after y is ignored).
std::vector<double> parse_shape(std::string_view text, const std::string& where) {
  std::vector<double> xy;
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && text[pos] == ' ') ++pos;
    if (pos >= text.size()) break;
    std::size_t end = text.find(' ', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view point = text.substr(pos, end - pos);
    double x = 0, y = 0;
    const auto comma = point.find(',');
    const bool ok = comma != std::string_view::npos &&
                    std::from_chars(point.data(), point.data() + comma, x).ec == std::errc() &&
                    std::from_chars(point.data() + comma + 1, point.data() + point.size(), y).ec == std::errc();
    if (!ok) throw OrchError(fmt::format("{}: shape point \"{}\" is not \"x,y\"", where, point));
    xy.push_back(x);
    xy.push_back(y);
    pos = end;
  }
  return xy;
}

Bounds bounds_of(const std::vector<double>& xy) {
  Bounds b{xy[0], xy[1], xy[0], xy[1]};
  for (std::size_t i = 0; i + 1 < xy.size(); i += 2) {
    b.min_x = std::min(b.min_x, xy[i]);
    b.max_x = std::max(b.max_x, xy[i]);
    b.min_y = std::min(b.min_y, xy[i + 1]);
    b.max_y = std::max(b.max_y, xy[i + 1]);
  }
  return b;
}

}  // namespace

std::vector<LaneShape> read_lane_shapes(const std::filesystem::path& net_file, std::optional<Bounds> within) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_file(net_file.c_str());
  if (!parsed)
    throw OrchError(fmt::format("{}: not a SUMO net: {} (at byte {})", net_file.string(), parsed.description(),
                                parsed.offset));
  const pugi::xml_node net = doc.child("net");
  if (!net) throw OrchError(net_file.string() + ": no <net> element");
  std::vector<LaneShape> lanes;
  for (const pugi::xml_node edge : net.children("edge")) {
    const std::string function = edge.attribute("function").as_string("normal");
    if (function != "normal" && function != "internal") continue;  // walkingarea, crossing, connector
    for (const pugi::xml_node lane : edge.children("lane")) {
      LaneShape s;
      s.id = lane.attribute("id").as_string();
      s.internal = function == "internal";
      s.width = lane.attribute("width").as_double(3.2);
      s.xy = parse_shape(lane.attribute("shape").as_string(), fmt::format("{}: lane {}", net_file.string(), s.id));
      if (s.xy.size() < 4) continue;  // nothing to draw
      if (within && !within->overlaps(bounds_of(s.xy))) continue;
      lanes.push_back(std::move(s));
    }
  }
  return lanes;
}

}  // namespace orch::report
