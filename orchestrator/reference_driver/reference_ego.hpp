#pragma once
// The reference driver at the engine seam: turns each WorldSnapshot into what the driver
// sees (perceive(), pure) and the driver's decision into the command SUMO executes
// (DriveSpeed). Both scenario runners use it the same way, on either backend.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/polyline.hpp"
#include "sim/world.hpp"
#include "reference_driver/r157_driver.hpp"

namespace orch::reference_driver {

// The ego's lane: its centre line (the path the driver keeps to) and width.
struct DrivingPath {
  Polyline line;
  double lane_width = 3.5;
  std::optional<double> end_s;  // where the ego's route ends on the line (its centre stops there)
  // Where a stop the scenario gives the ego (its end_position, as SUMO is told: edge, lane,
  // lane position of the centre) lies on the line; unset: stops are not followed.
  std::function<std::optional<double>(const sim::SetStop&)> stop_to_s;
};

// Actors by SUMO id: which are pedestrians or obstacles (the others are vehicles).
using ObjectKinds = std::map<std::string, ObjectKind>;

// Background vehicles' accelerations, from their speeds in consecutive snapshots (the
// snapshot carries none for them): a background leader braking hard is a risk too.
class NearbyMotion {
 public:
  // The acceleration of `id` since its last sighting (0 when first seen or seen again after
  // a gap); remembers this one.
  double accel(const std::string& id, double time, double speed);
  // Forgets vehicles not seen at `time` (called once per snapshot, after every accel()).
  void sweep(double time);

 private:
  struct Seen {
    double time = 0;
    double speed = 0;
    double accel = 0;
  };
  std::map<std::string, Seen> seen_;
};

// What the driver sees in `snap`: the ego (the tracked actor `ego`, a SUMO id) and every
// other present actor and nearby background vehicle within the perception range, in the
// path's frame; `path_s` is the ego's arc length at the last step (the search starts
// there; negative: search the whole path). Nullopt when the ego is not on the road.
// `motion`, if given, supplies the background vehicles' accelerations (else 0).
std::optional<DriverView> perceive(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked,
                                   const ObjectKinds& kinds, const std::string& ego, const DrivingPath& path,
                                   double path_s, double range, NearbyMotion* motion = nullptr);

// Any ego, whatever drives it, seen through the driver's eyes: the closest approach to what
// is ahead in its lane over the run (OpenSCENARIO runs have no metrics of their own yet).
class EgoWatch {
 public:
  EgoWatch(DrivingPath path, std::string ego, ObjectKinds kinds, double range)
      : path_(std::move(path)), ego_(std::move(ego)), kinds_(std::move(kinds)), range_(range) {}
  void step(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked);
  [[nodiscard]] const Exposure& exposure() const { return exposure_; }

 private:
  DrivingPath path_;
  std::string ego_;
  ObjectKinds kinds_;
  double range_;
  double path_s_ = -1;
  Exposure exposure_;
};

// Which of the orchestrator's own models drives: the R157 reference driver, or cruise (the set
// speed whatever is ahead: a system under test that does not react).
enum class OwnModel { R157, Cruise };

class ReferenceEgo {
 public:
  ReferenceEgo(R157Parameters parameters, DrivingPath path, std::string ego, ObjectKinds kinds, double step,
               double set_speed, OwnModel model = OwnModel::R157);

  // The scenario's commands of this step: a desired speed for the ego (its insertion's
  // max_speed, SetMaxSpeed) becomes the driver's set speed, a stop (SetStop) the end of its path.
  void observe(const std::vector<sim::Command>& commands);
  // The command that drives the ego in the next step (none while the ego is not on the
  // road); `events` gets what the driver noticed, for the run log.
  std::vector<sim::Command> drive(const sim::WorldSnapshot& snap, const std::vector<sim::TrackedActor>& tracked,
                                     std::vector<std::string>& events);

  [[nodiscard]] const R157Driver& driver() const { return driver_; }

 private:
  R157Driver driver_;
  DrivingPath path_;
  std::string ego_;
  ObjectKinds kinds_;
  double step_;
  double set_speed_;
  OwnModel model_;
  double path_s_ = -1;  // not located yet
  NearbyMotion nearby_motion_;
};

}  // namespace orch::reference_driver
