#pragma once
// An OpenDRIVE file as a SUMO net: netconvert --opendrive-files on a copy of the file in
// which every lane without a speed record gets one (the road's own <type><speed>, else the
// default of its road type, speed_for_road_type), with the project's lane type map
// (lane_type_map_xml). Cached per content: the same .xodr bytes give the same net file,
// built once, byte for byte the same on every machine.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.hpp"

namespace orch::opendrive {

struct SumoNet {
  std::filesystem::path net_file;
  std::string key;          // SHA-256 of the .xodr bytes and the conversion settings
  bool from_cache = false;  // false: netconvert ran now
  // What the copy netconvert reads leaves out or rewrites (netconvert_workarounds.hpp).
  std::vector<Diagnostic> warnings;
};

// Converts `xodr_file` into `cache_root`/<key>/ (or finds it there). Throws MapError with
// netconvert's output when the conversion fails.
SumoNet convert_to_sumo_net(const std::filesystem::path& xodr_file, const std::filesystem::path& cache_root);

// $ORCH_CACHE/opendrive, else $XDG_CACHE_HOME/orchestrator/opendrive, else
// ~/.cache/orchestrator/opendrive, else <tmp>/orchestrator-cache/opendrive.
std::filesystem::path default_net_cache();

// m/s for lanes of a road of OpenDRIVE type `road_type` without speed records.
double speed_for_road_type(std::string_view road_type);

// The netconvert type map: which OpenDRIVE lane types become which SUMO lanes.
std::string lane_type_map_xml();

// The .xodr text netconvert reads: speed records added where lanes of moving traffic lack them.
std::string with_lane_speeds(const std::string& xodr_text, const std::string& file_name);

// What convert_to_sumo_net gives netconvert: the lane speeds above, and the content netconvert
// refuses rewritten (netconvert_workarounds.hpp), each rewrite a warning.
struct NetconvertInput {
  std::string text;
  std::vector<Diagnostic> warnings;
};
NetconvertInput netconvert_input(const std::string& xodr_text, const std::string& file_name);

}  // namespace orch::opendrive
