#include "opendrive/xodr_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>
#include <string_view>

#include <fmt/format.h>

#include "core/plausible.hpp"
#include "core/suggest.hpp"
#include "xml/xml_source.hpp"

namespace orch::opendrive {
namespace {

using xml::XmlSource;

// A lane is at most a kilometre wide (docs/hardening.md).
constexpr double kMaxLaneWidth = 1000.0;
// Heights and rolls of a road's surface (docs/openscenario.md, "Elevation").
constexpr double kMaxHeight = 1e5;   // m
constexpr double kMaxRoll = 1.309;   // rad, 75 degrees

class Reader {
 public:
  explicit Reader(const XmlSource& source) : src_(source) {}

  RoadNetwork read() {
    const pugi::xml_node root = src_.root();
    if (std::string_view(root.name()) != "OpenDRIVE")
      src_.fail(root, fmt::format("expected the root element OpenDRIVE, found {}", root.name()));
    const pugi::xml_node header = root.child("header");
    if (header && header.attribute("revMajor") && number(header, "revMajor") != 1.0)
      src_.fail(header, fmt::format("OpenDRIVE revMajor {} is not supported (expected 1)",
                                    header.attribute("revMajor").value()));
    std::vector<Road> roads;
    for (const pugi::xml_node road : root.children("road")) roads.push_back(read_road(road));
    if (roads.empty()) src_.fail(root, "the OpenDRIVE file holds no road");
    std::vector<Junction> junctions;
    for (const pugi::xml_node junction : root.children("junction")) junctions.push_back(read_junction(junction));
    check_links(root, roads);
    RoadNetwork network(std::move(roads), std::move(junctions));
    network.set_signal_controllers(read_signal_controllers(root));
    network.set_geo_reference(read_geo_reference(header));
    return network;
  }

 private:
  // The header's geoReference (its text, usually CDATA) and offset; kept as written, checked
  // by PROJ only when a GeoPosition needs it (a map need not be on the earth to be driven).
  GeoReference read_geo_reference(const pugi::xml_node& header) const {
    GeoReference g;
    if (!header) return g;
    std::string text = header.child("geoReference").text().get();
    const auto first = text.find_first_not_of(" \t\r\n");
    const auto last = text.find_last_not_of(" \t\r\n");
    g.proj = first == std::string::npos ? "" : text.substr(first, last - first + 1);
    if (const pugi::xml_node offset = header.child("offset")) {
      g.x = number(offset, "x", 0.0);
      g.y = number(offset, "y", 0.0);
      g.z = number(offset, "z", 0.0);
      g.hdg = number(offset, "hdg", 0.0);
    }
    return g;
  }

  double number(const pugi::xml_node& node, const char* name, std::optional<double> fallback = {}) const {
    const pugi::xml_attribute a = node.attribute(name);
    if (!a) {
      if (fallback) return *fallback;
      throw ScenarioError(src_.where(node, name), fmt::format("missing attribute {}", name));
    }
    const char* text = a.value();
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (end == text || *end != '\0' || !std::isfinite(value))
      throw ScenarioError(src_.where(node, name), fmt::format("expected a number, found \"{}\"", text));
    // Positions and lengths no map can hold are refused here (core/plausible.hpp), before
    // any geometry is sampled along them.
    const std::string_view n(name);
    const auto quantity = n == "x" || n == "y" ? std::optional(Quantity::Coordinate)
                          : n == "s" || n == "length" || n == "sOffset" ? std::optional(Quantity::Length)
                                                                         : std::nullopt;
    if (quantity)
      if (const auto why = implausible(value, *quantity))
        throw ScenarioError(src_.where(node, name), fmt::format("{} {}", name, *why));
    return value;
  }

  // A whole number that fits an int (lane ids): 1e300 or 2.5 is an error, not a cast.
  int integer(const pugi::xml_node& node, const char* name) const {
    const double value = number(node, name);
    if (std::floor(value) != value || std::abs(value) > 1e9)
      throw ScenarioError(src_.where(node, name),
                          fmt::format("expected a whole number (a lane id), found \"{}\"", node.attribute(name).value()));
    return static_cast<int>(value);
  }

  CubicRecord cubic(const pugi::xml_node& node, const char* start) const {
    return {number(node, start), number(node, "a", 0.0), number(node, "b", 0.0), number(node, "c", 0.0),
            number(node, "d", 0.0)};
  }

  Shape shape(const pugi::xml_node& geometry) const {
    for (const pugi::xml_node child : geometry.children()) {
      if (child.type() != pugi::node_element) continue;
      const std::string_view kind = child.name();
      if (kind == "line") return Line{};
      if (kind == "arc") return Arc{number(child, "curvature")};
      if (kind == "spiral") return Spiral{number(child, "curvStart"), number(child, "curvEnd")};
      if (kind == "poly3")
        return Poly3{number(child, "a"), number(child, "b"), number(child, "c"), number(child, "d")};
      if (kind == "paramPoly3") {
        const std::string range = child.attribute("pRange").as_string("normalized");
        if (range != "normalized" && range != "arcLength")
          throw ScenarioError(src_.where(child, "pRange"),
                              fmt::format("expected pRange \"normalized\" or \"arcLength\", found \"{}\"", range));
        return ParamPoly3{number(child, "aU"), number(child, "bU"), number(child, "cU"), number(child, "dU"),
                          number(child, "aV"), number(child, "bV"), number(child, "cV"), number(child, "dV"),
                          range == "normalized"};
      }
      src_.fail(child, fmt::format("unknown geometry {}{}", kind,
                                   did_you_mean(kind, {"line", "arc", "spiral", "poly3", "paramPoly3"})));
    }
    src_.fail(geometry, "geometry without a shape (line, arc, spiral, poly3 or paramPoly3)");
  }

  double speed_mps(const pugi::xml_node& node) const {
    const double max = number(node, "max");
    const std::string unit = node.attribute("unit").as_string("m/s");
    if (unit == "m/s") return max;
    if (unit == "km/h") return max / 3.6;
    if (unit == "mph") return max * 0.44704;
    throw ScenarioError(src_.where(node, "unit"),
                        fmt::format("expected a speed unit m/s, km/h or mph, found \"{}\"", unit));
  }

  ContactPoint contact_point(const pugi::xml_node& node) const {
    const pugi::xml_attribute a = node.attribute("contactPoint");
    if (!a) return ContactPoint::None;
    const std::string_view value = a.value();
    if (value == "start") return ContactPoint::Start;
    if (value == "end") return ContactPoint::End;
    throw ScenarioError(src_.where(node, "contactPoint"),
                        fmt::format("expected contactPoint \"start\" or \"end\", found \"{}\"", value));
  }

  // <predecessor>/<successor> of a road's <link>.
  RoadLink road_link(const pugi::xml_node& node) const {
    RoadLink link;
    if (!node) return link;
    const std::string type = node.attribute("elementType").as_string("road");
    if (type == "road") link.kind = RoadLink::Kind::Road;
    else if (type == "junction") link.kind = RoadLink::Kind::Junction;
    else
      throw ScenarioError(src_.where(node, "elementType"),
                          fmt::format("expected elementType \"road\" or \"junction\", found \"{}\"{}", type,
                                      did_you_mean(type, {"road", "junction"})));
    link.id = node.attribute("elementId").as_string();
    if (link.id.empty()) throw ScenarioError(src_.where(node, "elementId"), "link without an elementId");
    link.contact = contact_point(node);
    return link;
  }

  std::optional<int> lane_link(const pugi::xml_node& node) const {
    if (!node) return std::nullopt;
    return integer(node, "id");
  }

  // The signal groups (<controller>); a control without a signalId names no signal.
  std::vector<SignalController> read_signal_controllers(const pugi::xml_node& root) const {
    std::vector<SignalController> out;
    for (const pugi::xml_node node : root.children("controller")) {
      SignalController c{node.attribute("id").as_string(), node.attribute("name").as_string(), {}};
      if (c.id.empty()) throw ScenarioError(src_.where(node, "id"), "controller without an id");
      for (const pugi::xml_node control : node.children("control"))
        if (const std::string signal = control.attribute("signalId").as_string(); !signal.empty())
          c.signals.push_back(signal);
      out.push_back(std::move(c));
    }
    return out;
  }

  Junction read_junction(const pugi::xml_node& node) const {
    Junction junction;
    junction.id = node.attribute("id").as_string();
    if (junction.id.empty()) throw ScenarioError(src_.where(node, "id"), "junction without an id");
    for (const pugi::xml_node c : node.children("connection")) {
      JunctionConnection connection;
      connection.id = c.attribute("id").as_string();
      connection.incoming_road = c.attribute("incomingRoad").as_string();
      connection.connecting_road = c.attribute("connectingRoad").as_string();
      // A direct junction (OpenDRIVE 1.7) links the incoming road straight to `linkedRoad`.
      if (connection.connecting_road.empty()) connection.connecting_road = c.attribute("linkedRoad").as_string();
      if (connection.incoming_road.empty() || connection.connecting_road.empty())
        src_.fail(c, "connection without incomingRoad, or without connectingRoad or linkedRoad");
      const ContactPoint contact = contact_point(c);
      connection.contact = contact == ContactPoint::None ? ContactPoint::Start : contact;
      for (const pugi::xml_node l : c.children("laneLink"))
        connection.lane_links.push_back({integer(l, "from"), integer(l, "to")});
      junction.connections.push_back(std::move(connection));
    }
    return junction;
  }

  // Every road a link or connection names exists (a dangling road link is a broken file).
  // A link to a junction the file does not define is a dead end: netconvert's OpenDRIVE
  // output links the roads at dead-end nodes to junctions it does not write.
  void check_links(const pugi::xml_node& root, const std::vector<Road>& roads) const {
    std::vector<std::string> road_ids;
    for (const Road& r : roads) road_ids.push_back(r.id);
    const std::set<std::string> known(road_ids.begin(), road_ids.end());
    const auto check = [&](const pugi::xml_node& at, const std::string& id) {
      if (!known.count(id))
        src_.fail(at, fmt::format("link to the unknown road \"{}\"{}", id, did_you_mean(id, road_ids)));
    };
    for (const pugi::xml_node road : root.children("road"))
      for (const char* end : {"predecessor", "successor"})
        if (const pugi::xml_node l = road.child("link").child(end))
          if (std::string_view(l.attribute("elementType").as_string("road")) == "road")
            check(l, l.attribute("elementId").as_string());
    for (const pugi::xml_node junction : root.children("junction"))
      for (const pugi::xml_node c : junction.children("connection")) {
        check(c, c.attribute("incomingRoad").as_string());
        check(c, c.attribute(c.attribute("connectingRoad") ? "connectingRoad" : "linkedRoad").as_string());
      }
  }

  Lane read_lane(const pugi::xml_node& node) const {
    Lane lane;
    lane.id = integer(node, "id");
    lane.type = node.attribute("type").as_string("none");
    if (node.child("border"))
      src_.fail(node.child("border"), "lane border records are not supported (use width records)");
    for (const pugi::xml_node w : node.children("width")) lane.widths.push_back(cubic(w, "sOffset"));
    std::stable_sort(lane.widths.begin(), lane.widths.end(),
                     [](const CubicRecord& a, const CubicRecord& b) { return a.s < b.s; });
    for (const pugi::xml_node sp : node.children("speed"))
      lane.speeds.push_back({number(sp, "sOffset", 0.0), speed_mps(sp)});
    for (const pugi::xml_node h : node.children("height")) {
      LaneHeight height{number(h, "sOffset", 0.0), number(h, "inner", 0.0), number(h, "outer", 0.0)};
      for (const auto& [value, name] : {std::pair{height.inner, "inner"}, {height.outer, "outer"}})
        if (std::abs(value) > kMaxHeight)
          throw ScenarioError(src_.where(h, name),
                              fmt::format("lane height {:g} m: a lane lies at most {:g} m above or below its road", value,
                                          kMaxHeight));
      lane.heights.push_back(height);
    }
    std::stable_sort(lane.heights.begin(), lane.heights.end(),
                     [](const LaneHeight& a, const LaneHeight& b) { return a.s_offset < b.s_offset; });
    lane.predecessor = lane_link(node.child("link").child("predecessor"));
    lane.successor = lane_link(node.child("link").child("successor"));
    return lane;
  }

  LaneSection read_section(const pugi::xml_node& node) const {
    LaneSection section;
    section.s = number(node, "s");
    for (const pugi::xml_node lane : node.child("left").children("lane")) section.left.push_back(read_lane(lane));
    for (const pugi::xml_node lane : node.child("right").children("lane")) section.right.push_back(read_lane(lane));
    std::sort(section.left.begin(), section.left.end(), [](const Lane& a, const Lane& b) { return a.id < b.id; });
    std::sort(section.right.begin(), section.right.end(), [](const Lane& a, const Lane& b) { return a.id > b.id; });
    // Lanes must be numbered 1..n to the left and -1..-n to the right without gaps.
    for (std::size_t i = 0; i < section.left.size(); ++i)
      if (section.left[i].id != static_cast<int>(i) + 1)
        src_.fail(node, fmt::format("left lanes must be numbered 1..{} without gaps", section.left.size()));
    for (std::size_t i = 0; i < section.right.size(); ++i)
      if (section.right[i].id != -static_cast<int>(i) - 1)
        src_.fail(node, fmt::format("right lanes must be numbered -1..-{} without gaps", section.right.size()));
    return section;
  }

  Road read_road(const pugi::xml_node& node) const {
    Road road;
    road.id = node.attribute("id").as_string();
    if (road.id.empty()) throw ScenarioError(src_.where(node, "id"), "road without an id");
    road.name = node.attribute("name").as_string();
    road.length = number(node, "length");
    road.junction = node.attribute("junction").as_string("-1");
    road.left_hand_traffic = std::string_view(node.attribute("rule").as_string("RHT")) == "LHT";
    road.predecessor = road_link(node.child("link").child("predecessor"));
    road.successor = road_link(node.child("link").child("successor"));
    for (const pugi::xml_node type : node.children("type")) {
      if (const pugi::xml_node speed = type.child("speed")) road.type_speed_mps = speed_mps(speed);
      if (road.type.empty()) road.type = type.attribute("type").as_string();
    }
    std::vector<Geometry> geometries;
    for (const pugi::xml_node g : node.child("planView").children("geometry")) {
      // A geometry of no length has no shape to sample (found by the soak: length -2000).
      const double length = number(g, "length");
      if (!(length > 0))
        throw ScenarioError(src_.where(g, "length"),
                            fmt::format("geometry length must be > 0 m, found {}", g.attribute("length").value()));
      geometries.push_back(
          Geometry{number(g, "s"), {number(g, "x"), number(g, "y"), number(g, "hdg")}, length, shape(g)});
    }
    if (geometries.empty()) src_.fail(node, "road without planView geometry");
    // The reference line is the road: its geometries cover the road's length (real files
    // agree to 1e-14 m). The soak found a road of 2,000 m with 2 m of reference line; its
    // positions lay off SUMO's net and libsumo crashed.
    double covered = 0.0;
    for (const Geometry& g : geometries) covered += g.length;
    if (std::abs(covered - road.length) > std::max(0.01, 1e-4 * road.length))
      throw ScenarioError(src_.where(node, "length"),
                          fmt::format("the road is {:g} m long but its planView geometries cover {:g} m", road.length,
                                      covered));
    road.plan_view = PlanView(std::move(geometries));
    const pugi::xml_node lanes = node.child("lanes");
    for (const pugi::xml_node offset : lanes.children("laneOffset")) road.lane_offsets.push_back(cubic(offset, "s"));
    std::stable_sort(road.lane_offsets.begin(), road.lane_offsets.end(),
                     [](const CubicRecord& a, const CubicRecord& b) { return a.s < b.s; });
    for (const pugi::xml_node section : lanes.children("laneSection")) road.sections.push_back(read_section(section));
    if (road.sections.empty()) src_.fail(node, "road without a laneSection");
    std::stable_sort(road.sections.begin(), road.sections.end(),
                     [](const LaneSection& a, const LaneSection& b) { return a.s < b.s; });
    for (const pugi::xml_node section : lanes.children("laneSection"))
      check_lane_widths(section, section_length(road, number(section, "s")));
    road.elevations = profile(node.child("elevationProfile"), "elevation", "s", road.length, kMaxHeight,
                              "the road's height reaches {:g} m: no road lies more than {:g} m above or below sea level");
    road.superelevations =
        profile(node.child("lateralProfile"), "superelevation", "s", road.length, kMaxRoll,
                "the road's roll reaches {:g} rad: at most {:g} rad (75 degrees), where a banked track's lanes still "
                "have a width seen from above");
    return road;
  }

  // The cubic records `element` of `holder` (a road's elevations, a lane's widths), sorted by
  // their start; each stays within `limit` in magnitude up to the next one or `end`.
  std::vector<CubicRecord> profile(const pugi::xml_node& holder, const char* element, const char* start, double end_of_last,
                                   double limit, const char* message) const {
    std::vector<std::pair<CubicRecord, pugi::xml_node>> records;
    for (const pugi::xml_node e : holder.children(element)) records.emplace_back(cubic(e, start), e);
    std::stable_sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.first.s < b.first.s; });
    std::vector<CubicRecord> out;
    for (std::size_t i = 0; i < records.size(); ++i) {
      const double end = i + 1 < records.size() ? records[i + 1].first.s : end_of_last;
      const double largest = records[i].first.largest_magnitude(std::max(0.0, end - records[i].first.s));
      if (!(largest <= limit))
        throw ScenarioError(src_.where(records[i].second, "a"), fmt::format(fmt::runtime(message), largest, limit));
      out.push_back(records[i].first);
    }
    return out;
  }

  // The length of the section starting at `s`: up to the next section, or the road's end.
  static double section_length(const Road& road, double s) {
    for (const LaneSection& next : road.sections)
      if (next.s > s) return next.s - s;
    return road.length - s;
  }

  // A lane is at most a kilometre wide anywhere along its width record, not only at its
  // start: the soak found a width of 3,000 km (a run of minutes instead of a second) and a
  // slope `b` of 9.2e18 (an abort).
  void check_lane_widths(const pugi::xml_node& section, double section_length) const {
    for (const char* side : {"left", "right"})
      for (const pugi::xml_node lane : section.child(side).children("lane"))
        (void)profile(lane, "width", "sOffset", section_length, kMaxLaneWidth,
                      "lane width reaches {:g} m within its record: a lane is at most {:g} m wide");
  }

  const XmlSource& src_;
};

}  // namespace

RoadNetwork read_xodr_file(const std::string& path) {
  const XmlSource source = XmlSource::load(path);
  return Reader(source).read();
}

RoadNetwork read_xodr_text(std::string text, const std::string& name) {
  const XmlSource source = XmlSource::parse(std::move(text), name);
  return Reader(source).read();
}

}  // namespace orch::opendrive
