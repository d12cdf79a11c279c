#pragma once
// OpenSCENARIO / OpenDRIVE text shared by the storyboard runtime tests: a straight two-lane
// road and the entities placed on it. Header only ("unit/openscenario_snippets.hpp").
#include <string>
#include <vector>

#include "openscenario/storyboard_runtime.hpp"

namespace orch::test {

// Road 0 along +x, 2 km; lane -1 centred at y = -1.75, lane -2 at y = -5.25.
inline const char* kStraightTwoLaneRoad = R"(<OpenDRIVE><header revMajor="1" revMinor="6"/>
<road id="0" length="2000" junction="-1"><planView><geometry s="0" x="0" y="0" hdg="0" length="2000"><line/></geometry></planView>
<lanes><laneSection s="0"><right>
 <lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
 <lane id="-2" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
</right></laneSection></lanes></road></OpenDRIVE>)";

// A 5 m x 2 m car whose box centre is 1.5 m ahead of its reference point.
inline std::string vehicle(const std::string& name) {
  return R"(<ScenarioObject name=")" + name + R"("><Vehicle name="car" vehicleCategory="car">
  <BoundingBox><Center x="1.5" y="0" z="0.9"/><Dimensions width="2" length="5" height="1.8"/></BoundingBox>
  <Performance maxSpeed="70" maxDeceleration="10" maxAcceleration="10"/>
  <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.8" trackWidth="1.68" positionX="3" positionZ="0.4"/>
  <RearAxle maxSteering="0" wheelDiameter="0.8" trackWidth="1.68" positionX="0" positionZ="0.4"/></Axles>
  </Vehicle></ScenarioObject>)";
}

// Init actions putting `name` on road 0's `lane` at `s`, driving at `speed`.
inline std::string place(const std::string& name, double s, int lane, double speed) {
  return R"(<Private entityRef=")" + name + R"("><PrivateAction><TeleportAction><Position><LanePosition roadId="0" laneId=")" +
         std::to_string(lane) + R"(" s=")" + std::to_string(s) + R"(" offset="0"/></Position></TeleportAction></PrivateAction>
  <PrivateAction><LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" dynamicsDimension="time" value="0"/>
  <SpeedActionTarget><AbsoluteTargetSpeed value=")" + std::to_string(speed) + R"("/></SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Private>)";
}

// Steps of 0.05 s until `t` or the storyboard's end.
inline void run_until(openscenario::StoryboardRuntime& runtime, double t) {
  while (runtime.time() < t - 1e-9 && !runtime.finished()) runtime.step(0.05);
}

// When `name` made `transition` (startTransition, endTransition, ...), in order.
inline std::vector<double> transition_times(const openscenario::StoryboardRuntime& runtime, const std::string& name,
                                            const std::string& transition) {
  std::vector<double> out;
  for (const openscenario::TransitionLog& l : runtime.log())
    if (l.name == name && l.transition == transition) out.push_back(l.time);
  return out;
}

}  // namespace orch::test
