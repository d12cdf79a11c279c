#include "opendrive/sumo_net.hpp"

#include <unistd.h>

#include <cstdlib>
#include <sstream>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/process.hpp"
#include "core/sumo_output.hpp"
#include "opendrive/netconvert_workarounds.hpp"
#include "xml/xml_source.hpp"

namespace orch::opendrive {
namespace fs = std::filesystem;

namespace {

// Bump when the conversion changes, so that old cache entries are not reused.
constexpr std::string_view kConversionVersion = "opendrive-sumo-net 3";

// netconvert copies the road's geoReference into the net's <location projParameter>, and
// SUMO then builds a PROJ transformation whenever it loads the net: PROJ opens and queries
// its SQLite database, ~5 % of the CPU time of a short run (docs/performance.md). Nothing of
// a run converts to longitude and latitude through SUMO, so the cached net carries none
// ("!", SUMO's "no projection"); the simulation is the same.
std::string without_projection(std::string net) {
  const std::size_t location = net.find("<location ");
  if (location == std::string::npos) return net;
  const std::string key = " projParameter=\"";
  const std::size_t start = net.find(key, location);
  const std::size_t element_end = net.find('>', location);
  if (start == std::string::npos || start > element_end) return net;
  const std::size_t value = start + key.size();
  const std::size_t end = net.find('"', value);
  if (end == std::string::npos) return net;
  net.replace(value, end - value, "!");
  return net;
}

bool carries_traffic(std::string_view lane_type) {
  for (const std::string_view t : {"driving", "entry", "exit", "onRamp", "offRamp", "mwyEntry", "mwyExit"})
    if (lane_type == t) return true;
  return false;
}

}  // namespace

double speed_for_road_type(std::string_view road_type) {
  // km/h; the common limits of the road classes (motorway: the usual advisory 130 km/h).
  struct Entry {
    std::string_view type;
    double kmh;
  };
  static constexpr Entry kSpeeds[] = {
      {"motorway", 130}, {"rural", 100},        {"townExpressway", 80}, {"town", 50},
      {"townArterial", 50}, {"townCollector", 50}, {"townLocal", 30},     {"townPrivate", 30},
      {"lowSpeed", 30},  {"townPlayStreet", 7}, {"bicycle", 25},        {"pedestrian", 5}};
  for (const Entry& e : kSpeeds)
    if (e.type == road_type) return e.kmh / 3.6;
  return 100 / 3.6;  // no or an unknown road type: a rural road
}

std::string lane_type_map_xml() {
  // Moving traffic on driving lanes (speeds come from the .xodr, see with_lane_speeds);
  // hard shoulders ("stop"), shoulders and restricted lanes are kept for scripted entities
  // but admit only the class "authority", so background traffic never uses them.
  const std::string cars = "disallow=\"pedestrian rail rail_urban rail_electric rail_fast tram ship\"";
  std::string out = "<types>\n";
  for (const char* t : {"driving", "entry", "exit", "onRamp", "offRamp", "mwyEntry", "mwyExit"})
    out += fmt::format("    <type id=\"{}\" priority=\"1\" speed=\"27.78\" width=\"3.50\" {}/>\n", t, cars);
  for (const char* t : {"stop", "shoulder", "restricted"})
    out += fmt::format("    <type id=\"{}\" priority=\"0\" speed=\"13.89\" width=\"2.50\" allow=\"authority\"/>\n", t);
  out += "    <type id=\"parking\" priority=\"0\" speed=\"1.39\" width=\"2.50\" allow=\"authority\"/>\n";
  // Sidewalks and cycle lanes take scripted entities too (they are SUMO vehicles of the class
  // "authority", openscenario_world.cpp: a pedestrian placed on a sidewalk), besides SUMO's
  // own pedestrians and bicycles.
  out += "    <type id=\"sidewalk\" priority=\"-2\" speed=\"2.78\" width=\"2.00\" allow=\"pedestrian authority\"/>\n";
  out += "    <type id=\"walking\" priority=\"-2\" speed=\"2.78\" width=\"2.00\" allow=\"pedestrian authority\"/>\n";
  out += "    <type id=\"biking\" priority=\"-1\" speed=\"5.56\" width=\"1.50\" allow=\"bicycle authority\"/>\n";
  out += "    <type id=\"tram\" priority=\"2\" speed=\"13.89\" width=\"3.50\" allow=\"tram\"/>\n";
  out += "    <type id=\"rail\" priority=\"3\" speed=\"33.33\" width=\"3.50\" allow=\"rail rail_urban rail_electric rail_fast\"/>\n";
  for (const char* t : {"none", "border", "median", "curb", "special1", "special2", "special3", "roadWorks",
                        "bidirectional"})
    out += fmt::format("    <type id=\"{}\" priority=\"0\" speed=\"1.39\" width=\"0.10\" disallow=\"all\" discard=\"true\"/>\n", t);
  return out + "</types>\n";
}

namespace {

void add_lane_speeds(const xml::XmlSource& source) {
  for (pugi::xml_node road : source.root().children("road")) {
    double speed = speed_for_road_type(road.child("type").attribute("type").as_string(""));
    if (const pugi::xml_node record = road.child("type").child("speed")) {
      const double max = record.attribute("max").as_double(0.0);
      const std::string unit = record.attribute("unit").as_string("m/s");
      speed = unit == "km/h" ? max / 3.6 : unit == "mph" ? max * 0.44704 : max;
    }
    for (pugi::xml_node section : road.child("lanes").children("laneSection"))
      for (const char* side : {"left", "right"})
        for (pugi::xml_node lane : section.child(side).children("lane")) {
          if (!carries_traffic(lane.attribute("type").as_string("")) || lane.child("speed")) continue;
          pugi::xml_node record = lane.append_child("speed");
          record.append_attribute("sOffset") = "0";
          record.append_attribute("max") = fmt::format("{:.4f}", speed).c_str();
          record.append_attribute("unit") = "m/s";
        }
  }
}

std::string printed(const xml::XmlSource& source) {
  std::ostringstream out;
  source.root().root().print(out, "  ", pugi::format_default, pugi::encoding_utf8);
  return out.str();
}

}  // namespace

std::string with_lane_speeds(const std::string& xodr_text, const std::string& file_name) {
  const xml::XmlSource source = xml::XmlSource::parse(xodr_text, file_name);
  add_lane_speeds(source);
  return printed(source);
}

NetconvertInput netconvert_input(const std::string& xodr_text, const std::string& file_name) {
  const xml::XmlSource source = xml::XmlSource::parse(xodr_text, file_name);
  NetconvertInput input;
  input.warnings = apply_netconvert_workarounds(source);
  add_lane_speeds(source);
  input.text = printed(source);
  return input;
}

fs::path default_net_cache() {
  if (const char* env = std::getenv("ORCH_CACHE"); env && *env) return fs::path(env) / "opendrive";
  if (const char* env = std::getenv("XDG_CACHE_HOME"); env && *env) return fs::path(env) / "orchestrator" / "opendrive";
  if (const char* env = std::getenv("HOME"); env && *env) return fs::path(env) / ".cache" / "orchestrator" / "opendrive";
  return fs::temp_directory_path() / "orchestrator-cache" / "opendrive";
}

SumoNet convert_to_sumo_net(const fs::path& xodr_file, const fs::path& cache_root) {
  const std::string text = read_file(xodr_file);
  SumoNet net;
  net.key = sha256_hex(std::string(kConversionVersion) + "\n" + lane_type_map_xml() + text);
  const fs::path dir = cache_root / net.key;
  net.net_file = dir / "net.net.xml";
  std::error_code ec;
  NetconvertInput input = netconvert_input(text, xodr_file.string());  // bad XML fails here
  net.warnings = std::move(input.warnings);  // also for a cached net: the run reports them every time
  if (fs::is_regular_file(net.net_file, ec)) {
    net.from_cache = true;
    return net;
  }
  const std::string& converted = input.text;
  // Built in a private folder and renamed into place: parallel runs of a batch may convert
  // the same road at once; one rename wins and the others find the finished entry.
  const fs::path work = cache_root / fmt::format("{}.tmp{}", net.key, ::getpid());
  fs::remove_all(work, ec);
  fs::create_directories(work, ec);
  if (ec) throw MapError(fmt::format("cannot create {}: {}", work.string(), ec.message()));
  write_file_atomically(work / "road.xodr", converted);
  write_file_atomically(work / "lanes.typ.xml", lane_type_map_xml());
  // Relative paths: netconvert copies its arguments into the net's header.
  const ProcessResult result = run_process(
      "netconvert",
      {"--opendrive-files", "road.xodr", "--type-files", "lanes.typ.xml", "--output-file", "net.net.xml",
       // SUMO coordinates == OpenDRIVE coordinates.
       "--offset.disable-normalization", "true", "--no-turnarounds", "true"},
      work);
  if (result.exit_code != 0) {
    fs::remove_all(work, ec);
    throw MapError(fmt::format("netconvert could not convert {} (exit status {}):\n{}", xodr_file.string(),
                               result.exit_code, result.output));
  }
  write_file_atomically(work / "net.net.xml",
                        without_projection(without_generation_date(read_file(work / "net.net.xml"))));
  fs::rename(work, dir, ec);
  if (ec) {
    fs::remove_all(work, ec);  // another process finished first; its entry is the same bytes
    if (!fs::is_regular_file(net.net_file))
      throw MapError(fmt::format("cannot store the converted net of {} in {}", xodr_file.string(), dir.string()));
  }
  return net;
}

}  // namespace orch::opendrive
