#include "openscenario/trailer_motion.hpp"

#include <cmath>

namespace orch::openscenario {
namespace {

double hitch_dx(const Entity& tractor) {
  return tractor.trailer_hitch_dx.value_or(tractor.box.center_x - tractor.box.length / 2);
}

double coupler_dx(const Entity& trailer) {
  return trailer.trailer_coupler_dx.value_or(trailer.box.center_x + trailer.box.length / 2);
}

opendrive::Pose2 hitch_point(const Entity& spec, const EntityState& tractor) {
  const double dx = hitch_dx(spec);
  return {tractor.pose.x + dx * std::cos(tractor.pose.heading), tractor.pose.y + dx * std::sin(tractor.pose.heading),
          tractor.pose.heading};
}

void pull(const Entity& tractor_spec, const EntityState& tractor, const Entity& trailer_spec, EntityState& trailer,
          const opendrive::RoadNetwork& roads, double dt) {
  const opendrive::Pose2 hitch = hitch_point(tractor_spec, tractor);
  const double bar = coupler_dx(trailer_spec);
  double heading = tractor.pose.heading;
  if (trailer.placed) {
    const double dx = hitch.x - trailer.pose.x;
    const double dy = hitch.y - trailer.pose.y;
    // The bar's direction; a reference point on the hitch (no bar) keeps its heading.
    heading = std::hypot(dx, dy) > 1e-9 ? std::atan2(dy, dx) : trailer.pose.heading;
    if (bar < 0) heading += M_PI;  // a coupler behind the reference point: the bar points back
  }
  const opendrive::Pose2 before = trailer.pose;
  trailer.pose = {hitch.x - bar * std::cos(heading), hitch.y - bar * std::sin(heading), heading};
  const double speed = tractor.speed * std::cos(tractor.pose.heading - heading);
  if (trailer.placed && dt > 0) {
    trailer.odometer += std::hypot(trailer.pose.x - before.x, trailer.pose.y - before.y);
    trailer.acceleration = (speed - trailer.speed) / dt;
  }
  trailer.speed = speed;
  trailer.placed = true;
  relocate(trailer, roads);
}

// The trailer's own motion ends: it is towed (or, disconnected, stands).
void stop_own_motion(EntityState& trailer) {
  trailer.speed_profile.reset();
  trailer.lateral_profile.reset();
  trailer.path.reset();
  trailer.route.clear();
  trailer.route_plan.clear();
  trailer.lateral_rate = 0;
}

}  // namespace

TrailerLinks initial_trailer_links(const Scenario& scenario) {
  TrailerLinks links;
  for (const Entity& e : scenario.entities)
    if (!e.trailer.empty()) links[e.name] = e.trailer;
  return links;
}

void connect_trailer(const Scenario& scenario, std::map<std::string, EntityState>& entities, TrailerLinks& links,
                     const std::string& tractor, const std::string& trailer, const opendrive::RoadNetwork& roads) {
  for (auto it = links.begin(); it != links.end();)  // a trailer has one tractor
    it = it->second == trailer ? links.erase(it) : std::next(it);
  links[tractor] = trailer;
  EntityState& towed = entities.at(trailer);
  stop_own_motion(towed);
  const EntityState& front = entities.at(tractor);
  if (front.placed) pull(*scenario.entity(tractor), front, *scenario.entity(trailer), towed, roads, 0);
}

void align_initial_trailers(const Scenario& scenario, std::map<std::string, EntityState>& entities,
                            TrailerLinks& links, const opendrive::RoadNetwork& roads) {
  std::map<std::string, bool> is_trailer;
  for (const auto& [tractor, trailer] : links) is_trailer[trailer] = true;
  for (const auto& [head, first] : TrailerLinks(links)) {
    if (is_trailer.contains(head)) continue;  // chains are aligned from their front vehicle
    std::string tractor = head;
    for (std::size_t n = 0; n <= links.size(); ++n) {  // bounded: a loop of links stops
      const auto link = links.find(tractor);
      if (link == links.end() || !entities.at(tractor).placed) break;
      EntityState& towed = entities.at(link->second);
      stop_own_motion(towed);
      towed.placed = false;  // straight behind its tractor, wherever Init teleported it
      pull(*scenario.entity(tractor), entities.at(tractor), *scenario.entity(link->second), towed, roads, 0);
      tractor = link->second;
    }
  }
}

void disconnect_trailer(std::map<std::string, EntityState>& entities, TrailerLinks& links, const std::string& tractor) {
  const auto it = links.find(tractor);
  if (it == links.end()) return;
  EntityState& trailer = entities.at(it->second);
  stop_own_motion(trailer);
  trailer.speed = 0;
  trailer.acceleration = 0;
  links.erase(it);
}

bool is_towed(const TrailerLinks& links, const std::string& entity) {
  for (const auto& [tractor, trailer] : links)
    if (trailer == entity) return true;
  return false;
}

void pull_trailers(const Scenario& scenario, std::map<std::string, EntityState>& entities, const TrailerLinks& links,
                   const opendrive::RoadNetwork& roads, double dt) {
  std::map<std::string, bool> is_trailer;
  for (const auto& [tractor, trailer] : links) is_trailer[trailer] = true;
  for (const auto& [head, first] : links) {
    if (is_trailer.contains(head)) continue;  // chains are pulled from their front vehicle
    std::string tractor = head;
    for (std::size_t n = 0; n <= links.size(); ++n) {  // bounded: a loop of links stops
      const auto link = links.find(tractor);
      if (link == links.end()) break;
      const EntityState& front = entities.at(tractor);
      if (!front.placed) break;
      pull(*scenario.entity(tractor), front, *scenario.entity(link->second), entities.at(link->second), roads, dt);
      tractor = link->second;
    }
  }
}

}  // namespace orch::openscenario
