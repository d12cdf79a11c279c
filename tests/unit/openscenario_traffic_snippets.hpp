#pragma once
// What the traffic-action unit tests share: road 0's SUMO net and the vehicles an
// OpenScenarioTraffic spawns in its first step.
#include <variant>
#include <vector>

#include "opendrive/sumo_lanes.hpp"
#include "openscenario/storyboard_runtime.hpp"
#include "run/openscenario_traffic.hpp"

namespace orch::test {

// Road 0's right side as netconvert makes it: edge -0, two lanes (lane -1 is SUMO lane 1).
inline const char* kRoadZeroNet = R"(<net><edge id="-0" from="a" to="b"><lane id="-0_0" index="0" length="2000" shape="0,0 1,1"/>
<lane id="-0_1" index="1" length="2000" shape="0,0 1,1"/></edge></net>)";

// The vehicles the runtime's traffic actions spawn at t = 0 with `seed`.
inline std::vector<sim::SpawnVehicle> first_step_spawns(const opendrive::SumoLaneIndex& lanes,
                                                        const openscenario::StoryboardRuntime& runtime, long long seed) {
  OpenScenarioTraffic traffic(lanes, seed);
  std::vector<sim::SpawnVehicle> out;
  for (auto& c : traffic.update(runtime.traffic(), runtime.entities(), {}, 0.0, 0.05))
    out.push_back(std::get<sim::SpawnVehicle>(c));
  return out;
}

}  // namespace orch::test
