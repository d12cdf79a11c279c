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

  // Makes SUMO's context subscription of `domain` (libsumo::CMD_GET_VEHICLE_VARIABLE or
  // CMD_GET_PERSON_VARIABLE) around `centre` reach at least `range` m with at least `vars`:
  // subscribes, or widens it, when it does not yet (SUMO answers at once, so results are
  // there in this step). Throws sumo::TraCIException when SUMO does not know the centre;
  // the table then stays as SUMO's subscriptions are.
  void subscribe(const std::string& centre, bool centre_person, int domain, double range,
                 const std::vector<int>& vars);

  // Before the centre is taken out of SUMO: its context subscriptions end (SUMO would
  // otherwise look for it in the next step).
  void forget(const std::string& centre) {
    for (auto it = entries_.begin(); it != entries_.end();) {
      const auto& [id, person, domain] = it->first;
      if (id != centre) {
        ++it;
        continue;
      }
      if (person) orch_sumo::Person::unsubscribeContext(id, domain, it->second.range);
      else orch_sumo::Vehicle::unsubscribeContext(id, domain, it->second.range);
      it = entries_.erase(it);
    }
  }

  // The objects of `domain` within `range` m of `centre`, with at least `vars` in their
  // results, by id (the centre itself included when it is of `domain`, as in SUMO);
  // subscribes first when needed.
  orch_sumo::SubscriptionResults within(const std::string& centre, bool centre_person, int domain, double range,
                                        const std::vector<int>& vars);

 private:
  struct Entry {
    double range = -1;
    std::vector<int> vars;
  };
  using Key = std::tuple<std::string, bool, int>;  // centre, centre is a person, domain

  const Entry& cover(const std::string& centre, bool centre_person, int domain, double range,
                     const std::vector<int>& vars);

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

inline const SharedContexts::Entry& SharedContexts::cover(const std::string& centre, bool centre_person, int domain,
                                                          double range, const std::vector<int>& vars) {
  const Key key{centre, centre_person, domain};
  const auto it = entries_.find(key);
  const auto in = [](const Entry& e, int v) { return std::find(e.vars.begin(), e.vars.end(), v) != e.vars.end(); };
  const auto covered = [&](int v) { return in(it->second, v); };
  // The common case, every step: already covered, nothing to allocate.
  if (it != entries_.end() && it->second.range >= range && covered(libsumo::VAR_POSITION) &&
      std::all_of(vars.begin(), vars.end(), covered))
    return it->second;
  Entry wider = it == entries_.end() ? Entry{} : it->second;
  wider.range = std::max(wider.range, range);
  if (!in(wider, libsumo::VAR_POSITION)) wider.vars.push_back(libsumo::VAR_POSITION);  // the range test needs it
  for (const int v : vars)
    if (!in(wider, v)) wider.vars.push_back(v);
  if (centre_person)
    orch_sumo::Person::subscribeContext(centre, domain, wider.range, wider.vars);
  else
    orch_sumo::Vehicle::subscribeContext(centre, domain, wider.range, wider.vars);
  Entry& slot = entries_[key];  // only once SUMO accepted
  slot = std::move(wider);
  return slot;
}

inline void SharedContexts::subscribe(const std::string& centre, bool centre_person, int domain, double range,
                                      const std::vector<int>& vars) {
  (void)cover(centre, centre_person, domain, range, vars);
}

inline orch_sumo::SubscriptionResults SharedContexts::within(const std::string& centre, bool centre_person,
                                                             int domain, double range,
                                                             const std::vector<int>& vars) {
  namespace sumo = orch_sumo;
  const Entry& e = cover(centre, centre_person, domain, range, vars);
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
