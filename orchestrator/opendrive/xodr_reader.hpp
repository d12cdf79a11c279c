#pragma once
// Reads an OpenDRIVE (.xodr) file into a RoadNetwork. Only what positions, lane types and
// driving on need is read (planView, laneOffset, lane sections, widths, types, speeds, road
// and lane links, junctions, the elevation profile and superelevation); road marks, lateral
// shapes, objects and signals are ignored; the signal groups (<controller>) are read.
// Errors name file, line and element path.
#include <string>

#include "opendrive/road_network.hpp"

namespace orch::opendrive {

// Throws ScenarioError (bad file) naming file, line and element.
RoadNetwork read_xodr_file(const std::string& path);
RoadNetwork read_xodr_text(std::string text, const std::string& name);

}  // namespace orch::opendrive
