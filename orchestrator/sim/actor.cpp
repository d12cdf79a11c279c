#include "sim/actor.hpp"

namespace orch::sim {

const char* to_string(ActorKind k) {
  switch (k) {
    case ActorKind::Vehicle: return "vehicle";
    case ActorKind::Pedestrian: return "pedestrian";
    case ActorKind::Obstacle: return "obstacle";
  }
  return "?";
}

}  // namespace orch::sim
