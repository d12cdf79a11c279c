#include "run/ego_link.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <type_traits>

namespace orch {

void hand_ego_to_plugin(std::vector<engine::Command>& commands) {
  const auto builtin_driving = [](const engine::Command& c) {
    return std::visit(
        [](const auto& cmd) {
          using T = std::decay_t<decltype(cmd)>;
          if constexpr (std::is_same_v<T, engine::SetMaxSpeed> || std::is_same_v<T, engine::SetStop>)
            return cmd.sumo_id == kEgoSumoId;
          return false;
        },
        c);
  };
  commands.erase(std::remove_if(commands.begin(), commands.end(), builtin_driving), commands.end());
  for (auto& c : commands) {
    if (auto* spawn = std::get_if<engine::SpawnVehicle>(&c); spawn && spawn->actor.sumo_id == kEgoSumoId) {
      // The vehicle type's own top speed, not the route's: a plug-in commanding 100 km/h on
      // a 60 km/h route must get 100 km/h.
      spawn->max_speed = 0;
    }
  }
}

std::optional<scenario::ActorId> plugin_driven_actor(const EgoLink* link,
                                                     const std::vector<engine::TrackedActor>& tracked) {
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
