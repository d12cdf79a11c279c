#pragma once
// The orchestrator's own collision test: every actor and every nearby background vehicle
// is an oriented rectangle (centre, heading, length, width); two touch when the rectangles
// overlap (separating-axis test). Contacts are tracked as episodes: one record when a pair
// starts touching, so a long scrape is one collision, not one per step.
#include <array>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/polyline.hpp"
#include "scenario_executor_engine/actor_table.hpp"
#include "scenario_executor_engine/sim_names.hpp"

namespace orch::engine {

// A contact between two bodies: scenario actors are named by their actor id ("3"),
// background vehicles by their SUMO id.
//
// Which evidence counts: between bodies the orchestrator sees (every actor, and the
// background vehicles in the snapshot's `nearby` list) its own test on the exact poses
// decides, so a contact begins on the very step the bodies first overlap. SUMO's reports
// are always recorded; they count only for a background vehicle the orchestrator does not
// see, where SUMO is the only witness.
struct Contact {
  double time = 0;
  std::string a;  // an actor id ("0", "1", ...) or a SUMO id of a background vehicle
  std::string b;
  Vec2 position_a{0, 0};
  Vec2 position_b{0, 0};
  std::string source;  // "geometry" (own test) or "sumo" (SUMO's report)
  std::string sumo_type;  // SUMO's collision type when reported by SUMO
  bool counted = true;    // false: recorded for information, the geometry test decides
};

class CollisionMonitor {
 public:
  explicit CollisionMonitor(const ActorTable& actors) : actors_(actors) {}

  // Tests the snapshot; returns the contacts that began on this step (both sources).
  std::vector<Contact> step(const WorldSnapshot& snap);
  // Actor ids in contact with anything on the last tested step (counted evidence only).
  [[nodiscard]] bool touching(ActorId id) const { return touching_.count(std::to_string(id)) > 0; }
  // The two actors' bodies in contact on the last tested step.
  [[nodiscard]] bool touching(ActorId a, ActorId b) const;
  [[nodiscard]] const std::vector<Contact>& all() const { return all_; }

 private:
  [[nodiscard]] std::string name_of_sumo(const std::string& sumo_id) const;

  const ActorTable& actors_;
  std::set<std::pair<std::string, std::string>> active_;       // pairs touching on the last step
  std::set<std::pair<std::string, std::string>> sumo_active_;  // pairs SUMO reported last step
  std::set<std::string> touching_;
  std::vector<Contact> all_;
};

}  // namespace orch::engine
