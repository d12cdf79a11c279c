#include "scenario_executor/model.hpp"

namespace orch::scenario {

position::Position StartPosition::position(ActorId ego) const {
  if (type == StartPositionType::Waypoint) return *waypoint;
  return position::RouteDistance{std::to_string(target.value_or(ego)), distance, measure == MeasureType::Surface,
                                 waypoint};
}

const char* to_string(Comparison c) {
  switch (c) {
    case Comparison::Greater: return ">";
    case Comparison::GreaterEqual: return ">=";
    case Comparison::Equal: return "=";
    case Comparison::LessEqual: return "<=";
    case Comparison::Less: return "<";
  }
  return "?";
}

}  // namespace orch::scenario
