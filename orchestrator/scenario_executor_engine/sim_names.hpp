#pragma once
// The ScenarioExecutor engine speaks the simulator contract's names unqualified: what it
// reads each step and the commands it returns (sim/world.hpp), the bodies it tests for
// contact (sim/box.hpp). Other layers say sim:: themselves.
#include "sim/box.hpp"
#include "sim/world.hpp"

namespace orch::engine {

using sim::ActorId;
using sim::ActorState;
using sim::box_corners;
using sim::boxes_touch;
using sim::Box;
using sim::Command;
using sim::DriveSpeed;
using sim::kLongWait;
using sim::kSignalBlinkerLeft;
using sim::kSignalBlinkerRight;
using sim::kSignalEmergencyBlue;
using sim::NearbyVehicle;
using sim::ReleaseActor;
using sim::RemoveActor;
using sim::SetMaxSpeed;
using sim::SetParameter;
using sim::SetPose;
using sim::SetRoute;
using sim::SetSignals;
using sim::SetStop;
using sim::SimCollision;
using sim::SpawnPerson;
using sim::SpawnVehicle;
using sim::TrackedActor;
using sim::WorldSnapshot;

}  // namespace orch::engine
