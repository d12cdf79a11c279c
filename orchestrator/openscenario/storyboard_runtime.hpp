#pragma once
// The OpenSCENARIO storyboard as it runs: element states (standby, running, complete) and
// transitions, triggers with condition edges and delays, and the scripted entities moved
// by their actions in the OpenDRIVE frame. Pure: no simulator call; the world it reads is
// its own entity states (a simulator adapter overwrites the ego's from SUMO).
//
// One step at time t: (A) entities advance from t - dt to t and actions whose motion is
// done end; (B) the storyboard's stop trigger, then act stop and start triggers, then event
// start triggers are evaluated on the states at t, and started actions take effect at t.
// A StoryboardElementStateCondition on a transition is true once for each transition: in
// the step it happened when the condition is evaluated after it, else in the next step
// (ASAM OpenSCENARIO: a transition is observed in the following evaluation), so a stop
// trigger on an instant action's endTransition fires although it is evaluated first.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"
#include "openscenario/traffic_book.hpp"

namespace orch::openscenario {

enum class ElementState { Standby, Running, Complete };

// One line of the storyboard log: an element's transition at a time.
struct TransitionLog {
  double time = 0;
  std::string type;        // story, act, maneuverGroup, maneuver, event, action
  std::string name;
  std::string transition;  // startTransition, endTransition, stopTransition, skipTransition
};

class StoryboardRuntime {
 public:
  // Throws MapError when an Init position cannot be placed on the roads. `seed`: the run's
  // (--seed), the source of what the storyboard leaves to chance (RandomRouteAction).
  StoryboardRuntime(const Scenario& scenario, const opendrive::RoadNetwork& roads, std::uint64_t seed = 0);
  ~StoryboardRuntime();
  StoryboardRuntime(const StoryboardRuntime&) = delete;
  StoryboardRuntime& operator=(const StoryboardRuntime&) = delete;

  // One step of `dt` seconds (see above). Does nothing once finished().
  void step(double dt);
  // An entity a simulator drives (the ego on SUMO), as the simulator has it now: replaces
  // the state the storyboard's own motion computed (road, lane and offset found from the
  // pose). Its speed profile, if any, keeps running: it is what the entity is asked to do.
  void observe(const std::string& name, const opendrive::Pose2& pose, double speed, double acceleration);
  [[nodiscard]] double time() const;
  [[nodiscard]] bool finished() const;  // the Storyboard's StopTrigger fired
  [[nodiscard]] const std::map<std::string, EntityState>& entities() const;
  [[nodiscard]] const std::vector<TransitionLog>& log() const;
  [[nodiscard]] ElementState state(const std::string& type, const std::string& name) const;
  // Parameter values now (ParameterSetAction / ParameterModifyAction change them).
  // Parameters by key: the scenario's by name, a Story's or Maneuver's as "<owner>/<name>".
  [[nodiscard]] const std::map<std::string, Parameter>& parameters() const;
  // Variable values now (VariableSetAction / VariableModifyAction change them).
  [[nodiscard]] const std::map<std::string, Parameter>& variables() const;
  // Monitor values now (MonitorDeclarations, 1.3; SetMonitorActions change them).
  [[nodiscard]] const std::map<std::string, bool>& monitors() const;
  // Which trailer each tractor tows now (tractor -> trailer).
  [[nodiscard]] const std::map<std::string, std::string>& trailers() const;
  // Each traffic signal's state now (OpenDRIVE signal id -> the file's state text).
  [[nodiscard]] const std::map<std::string, std::string>& signal_states() const;
  // The traffic TrafficActions started (and which a TrafficStopAction stopped).
  [[nodiscard]] const TrafficBook& traffic() const;
  // A traffic signal controller's phase now ("" before its first).
  [[nodiscard]] std::string signal_phase(const std::string& controller) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace orch::openscenario
