#pragma once
// The storyboard's TrafficActions on SUMO (openscenario/traffic_book.hpp says which traffic
// runs): vehicles SUMO's driver drives, spawned and removed through the simulator seam
// (SpawnVehicle with `traffic`, RemoveActor), never storyboard entities. Pure: it reads the
// entities' states and WorldSnapshot::traffic, and returns commands; its random choices come
// from the run's seed, so a run with the same seed spawns the same vehicles at the same places.
//
//   swarm   keeps up to numberOfVehicles vehicles of its own in the annulus around its central
//           entity: inside the ellipse (semiMajorAxis along the entity's heading, semiMinorAxis
//           across it, its centre `offset` ahead of the entity) and outside the inner circle
//           (innerRadius around that centre). A vehicle outside the ellipse is removed; missing
//           ones are spawned on free road places in the annulus (none within kSpacing m of
//           another vehicle or entity), facing their lane's direction of travel.
//   source  spawns one vehicle every 1/rate s from its start, on a free road place within
//           `radius` of its position (radius 0, or none free there: on the position's lane).
//   sink    removes the traffic vehicles (of any TrafficAction) and the background vehicles
//           (--traffic, the route file's) within `radius` of its position, at most `rate` per
//           second (no rate: all at once): the standard's sink takes every traffic participant.
//           Background vehicles are known only near the scenario's entities
//           (WorldSnapshot::nearby, within 75 m of one), so a sink farther from every entity
//           removes only TrafficAction vehicles.
//   area    (TrafficAreaAction, 1.3) keeps numberOfEntities vehicles of its own in its area
//           (run/traffic_area.hpp: a Polygon or RoadRanges): spawned on free road places of the
//           area, each on a route that stays on the area's lanes (straight on, as far as the
//           area's lanes go), so SUMO takes it out where it would leave; one seen outside the
//           area (outside the polygon; for road ranges: no place of the area within kPlaceStep m
//           along its lane and kAreaHalfWidth m across) is removed. Continuous:
//           missing vehicles are spawned again every step; else the area is filled once
//           (spawns SUMO did not insert are tried again) and empties as its vehicles leave.
//   stop    (TrafficStopAction) ends the named traffic: a swarm no longer spawns or removes, a
//           source no longer spawns, a sink no longer removes, an area neither; the vehicles drive on.
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "opendrive/sumo_lanes.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/traffic_book.hpp"
#include "run/run_result.hpp"
#include "sim/world.hpp"

namespace orch {

class OpenScenarioTraffic {
 public:
  static constexpr double kPlaceStep = 10.0;  // m between road places along a lane
  static constexpr double kSpacing = 20.0;    // m: no spawn this close to another body (as esmini's swarm)
  static constexpr double kInsertWait = 5.0;  // s: a spawn SUMO has not inserted by then is given up
  static constexpr double kAreaHalfWidth = 2.0;  // m across a lane's centre: still on it (an area's road range)

  // Road places: every kPlaceStep m along every lane for moving traffic (OpenDRIVE types
  // driving, entry, exit, on/off ramps) that SUMO's net has, junctions' connecting roads left out.
  OpenScenarioTraffic(const opendrive::SumoLaneIndex& lanes, long long seed);

  // The commands of this step (t): removals first, then spawns. `seen` is WorldSnapshot::traffic,
  // `background` WorldSnapshot::nearby (it may hold traffic vehicles too; they are told apart).
  std::vector<sim::Command> update(const openscenario::TrafficBook& book,
                                   const std::map<std::string, openscenario::EntityState>& entities,
                                   const std::vector<sim::NearbyVehicle>& seen, double t, double dt,
                                   const std::vector<sim::NearbyVehicle>& background = {});

  // Traffic vehicles now (spawned, not removed, not known to have left): per traffic serial.
  [[nodiscard]] int count(int serial) const;
  [[nodiscard]] int spawned_total() const { return next_id_; }
  [[nodiscard]] int removed_total() const { return removed_; }

  // What became of one traffic's vehicles (result.json's storyboard_traffic). For a swarm or a
  // source: spawned = active now + removed + left + not_inserted. For a sink: removed counts the
  // vehicles it removed (any traffic's and the background's), removed_background the latter.
  struct Tally {
    int spawned = 0;
    int removed = 0;       // its vehicles the TrafficActions removed (out of a swarm's area, in a sink)
    int left = 0;          // its vehicles that reached their route's end (SUMO took them out)
    int not_inserted = 0;  // spawns SUMO did not insert within kInsertWait (given up)
    int removed_background = 0;  // a sink's: background (--traffic) vehicles it removed
  };
  [[nodiscard]] Tally tally(int serial) const;

  struct Place {
    std::string road;
    int lane = 0;
    double s = 0;
    Vec2 point{0, 0};
    double heading = 0;  // direction of travel
    opendrive::SumoLane sumo;
  };
  [[nodiscard]] const std::vector<Place>& places() const { return places_; }

 private:
  struct Vehicle {
    int serial = 0;
    Vec2 position{0, 0};
    double spawned = 0;
    bool seen = false;
  };
  void swarm(const openscenario::Traffic& traffic, const openscenario::TrafficSwarmAction& spec,
             const std::map<std::string, openscenario::EntityState>& entities, double t,
             std::vector<sim::Command>& out);
  void source(const openscenario::Traffic& traffic, const openscenario::TrafficSourceAction& spec,
              const std::map<std::string, openscenario::EntityState>& entities, double t,
              std::vector<sim::Command>& out);
  void area(const openscenario::Traffic& traffic, const openscenario::TrafficAreaAction& spec,
            const std::map<std::string, openscenario::EntityState>& entities, double t, std::vector<sim::Command>& out);
  void sink(const openscenario::Traffic& traffic, const openscenario::TrafficSinkAction& spec, double dt,
            const std::vector<const sim::NearbyVehicle*>& background, std::vector<sim::Command>& out);
  [[nodiscard]] bool free(const Vec2& p, const std::map<std::string, openscenario::EntityState>& entities) const;
  // `share`: the vehicle's category (and a TrafficDistribution's size); `keep_on`: the lanes
  // (road, lane) its route may use (empty: straight on without limit).
  void spawn(int serial, const Place& place, double speed, double max_speed, const openscenario::TrafficCategoryShare& share,
             double t, std::vector<sim::Command>& out, const std::set<std::pair<std::string, int>>& keep_on = {});
  // `by`: the traffic whose action removed it (0: given up, not inserted).
  void remove(const std::string& id, int by, std::vector<sim::Command>& out);
  std::uint64_t draw(std::uint64_t n) { return n == 0 ? 0 : rng_() % n; }
  double uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  openscenario::TrafficCategoryShare category(const std::vector<openscenario::TrafficCategoryShare>& shares);

  const opendrive::SumoLaneIndex& lanes_;
  std::vector<Place> places_;
  std::mt19937_64 rng_;
  std::map<std::string, Vehicle> vehicles_;  // by SUMO id
  std::map<int, int> spawned_by_source_;     // serial -> vehicles spawned so far
  std::map<int, double> sink_credit_;        // serial -> removals due (rate x time) not yet made
  std::map<int, Tally> tallies_;             // serial -> what became of its vehicles
  std::map<int, std::vector<std::size_t>> area_places_;  // an area's serial -> its places (indices)
  std::set<std::string> removed_background_;  // this step's: a vehicle two sinks reach is removed once
  int next_id_ = 0;
  int removed_ = 0;
};

// What one TrafficAction did (result.json's storyboard_traffic), and run.log's line of it.
TrafficActionRecord traffic_record(const openscenario::Traffic& t, const OpenScenarioTraffic& traffic);
std::string traffic_outcome(const TrafficActionRecord& record);

}  // namespace orch
