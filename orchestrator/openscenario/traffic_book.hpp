#pragma once
// Which traffic the storyboard's TrafficActions have started, and which a TrafficStopAction
// has stopped (pure). A traffic action takes no simulation time (the standard, 1.3, 7.5.2:
// "All actions that do not assign control strategies are completed immediately"): it ends as
// it starts, and the traffic it defines lives on until a TrafficStopAction names it or the run
// ends. The simulator side (run/openscenario_traffic.hpp) spawns and removes SUMO's vehicles
// by this book.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/polyline.hpp"
#include "map/position_resolver.hpp"
#include "openscenario/model.hpp"

namespace orch::openscenario {

struct Traffic {
  int serial = 0;    // 1, 2, ... in the order started: which traffic a vehicle belongs to
  std::string name;  // the trafficName ("" none)
  std::variant<TrafficSwarmAction, TrafficSourceAction, TrafficSinkAction, TrafficAreaAction> spec;
  std::optional<position::ResolvedPosition> place;  // a source's or sink's position, resolved when it started
  double started = 0;
  std::optional<double> stopped;  // when a TrafficStopAction ended it
  std::vector<Vec2> polygon;      // a TrafficAreaAction's Polygon, its corners resolved when it started
};

class TrafficBook {
 public:
  void start(Traffic traffic, double t) {
    traffic.serial = static_cast<int>(traffic_.size()) + 1;
    traffic.started = t;
    traffic_.push_back(std::move(traffic));
  }
  // Stops every running traffic of that name; false when none runs.
  bool stop(const std::string& name, double t) {
    bool any = false;
    for (Traffic& traffic : traffic_)
      if (traffic.name == name && !traffic.stopped) {
        traffic.stopped = t;
        any = true;
      }
    return any;
  }
  [[nodiscard]] const std::vector<Traffic>& all() const { return traffic_; }

 private:
  std::vector<Traffic> traffic_;
};

}  // namespace orch::openscenario
