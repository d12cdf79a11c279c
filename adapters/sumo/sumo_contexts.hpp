#pragma once
// SUMO keeps one context subscription per object and context domain: a second
// subscribeContext for the same pair replaces the first. Two parts of the orchestrator want
// them: the world reader (the vehicles within 75 m of each scenario actor, every step) and an
// ego plug-in's context subscriptions (any object, domain, range and variables). They share
// SUMO's through this table: each pair is subscribed once, at the largest range and with
// every variable anyone asked for, and each asker keeps the objects within its own range by
// SUMO's own test (the 2-D distance between the two positions, as libsumo's lane visitor
// measures it). SUMO finds the objects through its lane tree, looking only at lanes near the
// centre, so nobody here ever lists every vehicle.
//
// Process-wide, like SUMO's connection itself (libsumo: the one simulation of the process;
// libtraci: its default connection). Compiled once per client library (sumo_api.hpp), hence
// the namespace named after it.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "sumo_api.hpp"

namespace orch::ORCH_SUMO_CONCAT(contexts_, ORCH_SUMO_NS) {

class SharedContexts {
 public:
  // A new simulation: SUMO has no subscriptions.
  void reset() { entries_.clear(); }

  // The objects of `domain` (libsumo::CMD_GET_VEHICLE_VARIABLE or CMD_GET_PERSON_VARIABLE)
  // within `range` m of `centre`, with at least `vars` in their results, by id (the centre
  // itself included when it is of `domain`, as in SUMO). Subscribes first, or widens SUMO's
  // subscription, when it does not cover the request yet. Throws sumo::TraCIException when
  // SUMO does not know the centre.
  orch_sumo::SubscriptionResults within(const std::string& centre, bool centre_person, int domain, double range,
                                        const std::vector<int>& vars);

 private:
  struct Entry {
    double range = -1;
    std::vector<int> vars;
  };
  using Key = std::tuple<std::string, bool, int>;  // centre, centre is a person, domain

  // SUMO files a centre's context results by the centre alone: with both domains subscribed
  // around one centre the two answers arrive as one table.
  [[nodiscard]] bool mixed(const std::string& centre, bool centre_person) const {
    return entries_.count({centre, centre_person, libsumo::CMD_GET_VEHICLE_VARIABLE}) > 0 &&
           entries_.count({centre, centre_person, libsumo::CMD_GET_PERSON_VARIABLE}) > 0;
  }

  std::map<Key, Entry> entries_;
};

// The table of this process's SUMO connection for this client library.
SharedContexts& shared_contexts();

inline orch_sumo::SubscriptionResults SharedContexts::within(const std::string& centre, bool centre_person,
                                                             int domain, double range,
                                                             const std::vector<int>& vars) {
  namespace sumo = orch_sumo;
  const Key key{centre, centre_person, domain};
  Entry& e = entries_[key];
  const Entry before = e;
  bool changed = range > e.range;
  std::vector<int> wanted = vars;
  wanted.push_back(libsumo::VAR_POSITION);  // the range test needs it
  for (const int v : wanted)
    if (std::find(e.vars.begin(), e.vars.end(), v) == e.vars.end()) {
      e.vars.push_back(v);
      changed = true;
    }
  if (changed) {
    const double subscribed = std::max(range, e.range);
    // SUMO answers a (re)subscription at once: the results below are this step's.
    try {
      if (centre_person)
        sumo::Person::subscribeContext(centre, domain, subscribed, e.vars);
      else
        sumo::Vehicle::subscribeContext(centre, domain, subscribed, e.vars);
    } catch (...) {
      // SUMO kept what it had (if anything): so does the table.
      if (before.range < 0)
        entries_.erase(key);
      else
        e = before;
      throw;
    }
    e.range = subscribed;
  }
  sumo::SubscriptionResults found = centre_person ? sumo::Person::getContextSubscriptionResults(centre)
                                                  : sumo::Vehicle::getContextSubscriptionResults(centre);
  const bool both = mixed(centre, centre_person);
  // Empty also when the centre has left SUMO (its subscriptions went with it).
  if (found.empty() || (e.range <= range && !both)) return found;
  sumo::TraCIPosition at;
  if (e.range > range) at = centre_person ? sumo::Person::getPosition(centre) : sumo::Vehicle::getPosition(centre);
  for (auto it = found.begin(); it != found.end();) {
    bool keep = true;
    if (e.range > range) {
      const auto p = it->second.find(libsumo::VAR_POSITION);
      const auto* pos = p == it->second.end() ? nullptr : dynamic_cast<const sumo::TraCIPosition*>(p->second.get());
      if (pos == nullptr) {
        keep = false;  // an object of the other domain
      } else {
        const double dx = pos->x - at.x, dy = pos->y - at.y;
        keep = std::sqrt(dx * dx + dy * dy) <= range;
      }
    }
    if (keep && both) {
      try {  // one cheap getter: SUMO throws for an id it does not know in this domain
        if (domain == libsumo::CMD_GET_PERSON_VARIABLE)
          (void)sumo::Person::getTypeID(it->first);
        else
          (void)sumo::Vehicle::getTypeID(it->first);
      } catch (const sumo::TraCIException&) {
        keep = false;
      }
    }
    it = keep ? std::next(it) : found.erase(it);
  }
  return found;
}

}  // namespace orch::ORCH_SUMO_CONCAT(contexts_, ORCH_SUMO_NS)
