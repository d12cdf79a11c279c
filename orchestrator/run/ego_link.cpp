#include "run/ego_link.hpp"

#include <fmt/format.h>


namespace orch {

std::optional<sim::ActorId> plugin_driven_actor(const EgoLink* link,
                                                     const std::vector<sim::TrackedActor>& tracked) {
  if (!link || !link->driving()) return std::nullopt;
  for (const auto& t : tracked)
    if (t.sumo_id == kEgoSumoId) return t.id;
  return std::nullopt;
}

std::string describe(const EgoLinkReport& r) {
  if (r.peer.empty()) return fmt::format("ego plug-in: none connected to {}", r.listen);
  long long total = 0;
  for (const auto& [name, n] : r.commands) total += n;
  return fmt::format("ego plug-in {}{}: {} step(s) driven, {} command(s), {} distinct; {}", r.peer,
                     r.client.empty() ? "" : " (" + r.client + ")", r.steps_driven, total, r.commands.size(), r.end);
}

}  // namespace orch
