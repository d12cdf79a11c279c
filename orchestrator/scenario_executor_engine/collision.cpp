#include "scenario_executor_engine/collision.hpp"

#include <array>
#include <cmath>

namespace orch::engine {

namespace {

std::pair<std::string, std::string> ordered(const std::string& a, const std::string& b) {
  return a < b ? std::pair{a, b} : std::pair{b, a};
}

}  // namespace

std::string CollisionMonitor::name_of_sumo(const std::string& sumo_id) const {
  const ActorSlot* slot = actors_.find_sumo(sumo_id);
  return slot ? std::to_string(slot->spec.id) : sumo_id;
}

std::vector<Contact> CollisionMonitor::step(const WorldSnapshot& snap) {
  struct Body {
    std::string name;
    Box box;
    bool actor;
  };
  std::vector<Body> bodies;
  for (const auto& a : snap.actors) {
    if (!a.present) continue;
    const ActorSlot* slot = actors_.find(a.id);
    if (!slot) continue;
    bodies.push_back({std::to_string(a.id), Box{a.position, a.heading, slot->model.length, slot->model.width}, true});
  }
  for (const auto& v : snap.nearby)
    bodies.push_back({v.sumo_id, Box{v.position, v.heading, v.length, v.width}, false});

  std::vector<Contact> started;
  std::set<std::pair<std::string, std::string>> now;
  touching_.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies[i].actor) continue;  // background-only pairs are SUMO's business
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      if (!boxes_touch(bodies[i].box, bodies[j].box)) continue;
      const auto key = ordered(bodies[i].name, bodies[j].name);
      now.insert(key);
      touching_.insert(bodies[i].name);
      if (bodies[j].actor) touching_.insert(bodies[j].name);
      if (!active_.count(key))
        started.push_back({snap.time, bodies[i].name, bodies[j].name, bodies[i].box.centre, bodies[j].box.centre,
                           "geometry", "", true});
    }
  }
  active_ = std::move(now);

  auto seen = [&](const std::string& sumo_id) {
    if (actors_.find_sumo(sumo_id)) return true;
    for (const auto& v : snap.nearby)
      if (v.sumo_id == sumo_id) return true;
    return false;
  };
  std::set<std::pair<std::string, std::string>> sumo_now;
  for (const auto& c : snap.collisions) {
    const std::string a = name_of_sumo(c.collider);
    const std::string b = name_of_sumo(c.victim);
    const auto key = ordered(a, b);
    sumo_now.insert(key);
    const bool counted = !seen(c.collider) || !seen(c.victim);
    if (counted) {
      if (actors_.find_sumo(c.collider)) touching_.insert(a);
      if (actors_.find_sumo(c.victim)) touching_.insert(b);
    }
    if (sumo_active_.count(key)) continue;
    Contact contact{snap.time, a, b, {0, 0}, {0, 0}, "sumo", c.type, counted};
    for (const auto& s : snap.actors) {
      if (std::to_string(s.id) == a) contact.position_a = s.position;
      if (std::to_string(s.id) == b) contact.position_b = s.position;
    }
    for (const auto& v : snap.nearby) {
      if (v.sumo_id == a) contact.position_a = v.position;
      if (v.sumo_id == b) contact.position_b = v.position;
    }
    started.push_back(contact);
  }
  sumo_active_ = std::move(sumo_now);
  all_.insert(all_.end(), started.begin(), started.end());
  return started;
}

bool CollisionMonitor::touching(ActorId a, ActorId b) const {
  // Actors are always seen, so the own geometry test decides for them (as for touching(id)).
  return active_.count(ordered(std::to_string(a), std::to_string(b))) > 0;
}

}  // namespace orch::engine
