#pragma once
// A scenario without a road: OpenSCENARIO's RoadNetwork may leave out the LogicFile (esmini's
// parking-lot and off-road examples place everything by world positions), but SUMO needs a
// net. The run gets a generated one: a single straight "parking" road far from any scene,
// where each entity is inserted into SUMO before the storyboard moves it to its world
// position (moveToXY, keepRoute 2: off every lane). The storyboard itself runs on an empty
// road network (openscenario/entity_motion.hpp: an entity on no road keeps its heading).
#include <filesystem>
#include <string>

#include "opendrive/sumo_net.hpp"

namespace orch {

// The parking road's OpenDRIVE id and the lane entities are inserted on.
inline constexpr const char* kParkingRoadId = "orch_parking";
inline constexpr int kParkingLane = -1;
inline constexpr double kParkingRoadLength = 2000.0;

// The OpenDRIVE text of the parking road (one right lane, far south-west of the origin).
std::string parking_road_xodr();

// Writes the parking road into `cache_root`/roadless/ and converts it (cached like any road).
// `xodr_file` receives the road file's path (the lane index reads it).
opendrive::SumoNet roadless_sumo_net(const std::filesystem::path& cache_root, std::filesystem::path& xodr_file);

// Where along the parking lane entity number `index` is inserted: 20 m apart, so that SUMO
// inserts every one at once (an occupied place would delay its insertion).
double parking_place(std::size_t index);

}  // namespace orch
