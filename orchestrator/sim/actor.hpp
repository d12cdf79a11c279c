#pragma once
// What the simulator knows of a scenario actor, whichever language placed it: its id, its
// kind and its model (size, SUMO class and shape).
#include <string>

namespace orch::sim {

// A scenario actor's id: the ScenarioExecutor format's actor id, or an OpenSCENARIO
// entity's index in the file.
using ActorId = int;

enum class ActorKind { Vehicle, Pedestrian, Obstacle };
const char* to_string(ActorKind k);

struct ModelInfo {
  std::string id;        // exact model id, or a pattern ending in '*' ("walker.pedestrian.*")
  ActorKind kind = ActorKind::Vehicle;
  double length = 0;     // m
  double width = 0;      // m
  double height = 0;     // m
  std::string vclass;    // SUMO vehicle class (vehicles and obstacles)
  std::string gui_shape; // SUMO guiShape, for sumo-gui
  bool emergency = false;  // has special1 lights / a siren
};

}  // namespace orch::sim

namespace orch {
// The whole project's vocabulary: every layer above says ActorKind and ModelInfo.
using sim::ActorKind;
using sim::ModelInfo;
using sim::to_string;
}  // namespace orch
