#pragma once
// An OpenSCENARIO run as the step loop's observers see it (run_observer.hpp), so that the
// metrics and criteria of ScenarioExecutor runs measure its entities the same way:
//  - actors are the entities SUMO knows (OpenScenarioActors::tracked()), named by entity
//    name in the outputs; pedestrians and misc objects are measured against, not measured;
//  - an entity's path (where its leader and follower are searched) is the centre line of the
//    OpenDRIVE lane it was first placed in, in its driving direction (the ego's watch uses the same);
//  - contacts are SUMO's collision reports between an entity and any body, each pair once;
//  - there are no scenes: the "ending" is the Storyboard's StopTrigger.
// Pure apart from reading the road geometry.
#include <map>
#include <set>
#include <utility>

#include "opendrive/road_network.hpp"
#include "openscenario/entity_motion.hpp"
#include "openscenario/model.hpp"
#include "run/openscenario_world.hpp"
#include "run/run_observer.hpp"

namespace orch {

class OpenScenarioRun : public ObservedRun {
 public:
  OpenScenarioRun(const openscenario::Scenario& scenario, const opendrive::RoadNetwork& roads,
                  const OpenScenarioActors& actors);

  // The step the observers see next: the snapshot read after storyboard time `time` (its
  // rows carry that time, like trace.csv), the entities as the storyboard has them, and
  // whether the StopTrigger has fired.
  void update(const sim::WorldSnapshot& snapshot, double time,
              const std::map<std::string, openscenario::EntityState>& entities, bool stop_trigger_fired);

  [[nodiscard]] const sim::WorldSnapshot& judged() const override { return snapshot_; }
  [[nodiscard]] std::optional<sim::ActorId> ego() const override;
  [[nodiscard]] std::optional<ObservedBody> body(sim::ActorId id) const override;
  [[nodiscard]] const Polyline* path_of(sim::ActorId id) const override;
  [[nodiscard]] int scene() const override { return 0; }
  [[nodiscard]] bool ending_reached() const override { return stop_trigger_fired_; }
  [[nodiscard]] const std::vector<engine::SceneVisit>& visits() const override { return visits_; }
  [[nodiscard]] const std::vector<engine::Contact>& contacts() const override { return contacts_; }

  // The entity's run index (result.json actors[].actor_id), nullopt for a name it does not have.
  [[nodiscard]] std::optional<sim::ActorId> id_of(const std::string& name) const;

 private:
  void record_contacts(const sim::WorldSnapshot& snapshot, double time);

  const openscenario::Scenario& scenario_;
  const opendrive::RoadNetwork& roads_;
  const OpenScenarioActors& actors_;
  sim::WorldSnapshot snapshot_;
  std::map<sim::ActorId, Polyline> paths_;
  std::vector<engine::SceneVisit> visits_;  // always empty
  std::vector<engine::Contact> contacts_;
  std::set<std::pair<std::string, std::string>> touched_;  // pairs already in contacts_
  bool stop_trigger_fired_ = false;
};

}  // namespace orch
