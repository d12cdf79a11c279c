#pragma once
// What the TraCI server needs from the simulated world: reads of SUMO's variables and the
// ego's commands. Implemented on SUMO by adapters/sumo/sumo_ego_control.cpp (compiled for
// libsumo and libtraci, so a plug-in sees the same on both backends) and by a table in the
// unit tests. Plain C++: no SUMO and no Asio here.
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "traci_server/traci_wire.hpp"

namespace orch::traci {

enum class Domain { Simulation, Vehicle, Person };

// SUMO refused one request (unknown vehicle, lane index out of range, ...): the plug-in gets
// an error status with this message and the connection stays up.
class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A valid TraCI request the orchestrator does not serve: "not implemented" status.
class NotImplemented : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The ego commands a plug-in may send (TraCI vehicle state changes).
struct SetSpeed {
  double speed = 0;  // m/s; negative gives control back to SUMO's car-following
};
struct SlowDown {
  double speed = 0;
  double duration = 0;  // s
};
struct ChangeLane {
  int lane = 0;
  double duration = 0;
};
struct MoveToXY {
  std::string edge;
  int lane = 0;
  double x = 0, y = 0, angle = 0;
  int keep_route = 1;
  double match_threshold = 100;
};
struct SetSignals {
  int signals = 0;
};
struct SetSpeedMode {
  int mode = 0;
};
struct SetLaneChangeMode {
  int mode = 0;
};
using EgoCommand = std::variant<SetSpeed, SlowDown, ChangeLane, MoveToXY, SetSignals, SetSpeedMode, SetLaneChangeMode>;

class EgoWorld {
 public:
  virtual ~EgoWorld() = default;
  // The world advanced: values read before are stale.
  virtual void new_step() = 0;
  // The plug-in takes the ego over (called once, when it connects).
  virtual void take_over_ego() = 0;
  // Whether the variable is served (without reading it): subscriptions are checked once.
  [[nodiscard]] virtual bool supports(Domain domain, int variable) const = 0;
  [[nodiscard]] virtual bool exists(Domain domain, const std::string& id) = 0;
  // One variable of one object now, as SUMO reports it (SUMO's frame: vehicle positions are
  // the front bumper's centre, angles in degrees clockwise from north). `parameter` is the
  // extra argument of VAR_LEADER (distance) and VAR_PARAMETER (key). Throws WorldError or
  // NotImplemented.
  virtual Value read(Domain domain, int variable, const std::string& id, const std::optional<Value>& parameter) = 0;
  // The objects of `context` within `range` m of `centre`, in id order: a context
  // subscription's answer. Both domains are Vehicle or Person (the session serves no other).
  // SUMO's test: the 2-D distance between their positions; the centre itself counts when it
  // is of `context`. `variables` are those the subscription will read of each (a hint: an
  // implementation may fetch them with the search). Throws WorldError when the centre is not
  // in the simulation.
  virtual std::vector<std::string> objects_in_range(Domain centre_domain, const std::string& centre, Domain context,
                                                    double range, const std::vector<int>& variables) = 0;
  // A command for a vehicle (the session has checked that it is the ego). Throws WorldError.
  virtual void command(const std::string& vehicle, const EgoCommand& command) = 0;
};

}  // namespace orch::traci
