#include "run/openscenario_traffic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "opendrive/lane_graph.hpp"
#include "opendrive/sumo_route.hpp"
#include "run/traffic_area.hpp"

namespace orch {

namespace {

bool moving_traffic_lane(const std::string& type) {
  for (const char* t : {"driving", "entry", "exit", "onRamp", "offRamp", "mwyEntry", "mwyExit"})
    if (type == t) return true;
  return false;
}

// A SUMO vehicle of the OpenSCENARIO vehicle category (the TrafficDefinition's), in a typical
// size, or in its own (a TrafficDistribution's vehicle template's BoundingBox).
ModelInfo traffic_model(const openscenario::TrafficCategoryShare& share) {
  const std::string& category = share.category;
  ModelInfo m;
  m.kind = ActorKind::Vehicle;
  m.id = category;
  struct Kind {
    const char* category;
    const char* vclass;
    const char* shape;
    double length, width, height;
  };
  static constexpr Kind kKinds[] = {
      {"van", "delivery", "delivery", 5.0, 2.0, 2.2},       {"truck", "truck", "truck", 12.0, 2.5, 3.5},
      {"semitrailer", "truck", "truck", 16.5, 2.55, 4.0},  {"trailer", "truck", "truck", 12.0, 2.5, 3.5},
      {"bus", "bus", "bus", 12.0, 2.5, 3.2},               {"motorbike", "motorcycle", "motorcycle", 2.2, 0.9, 1.5},
      {"bicycle", "bicycle", "bicycle", 1.8, 0.65, 1.7},
  };
  m.vclass = "passenger";
  m.gui_shape = "passenger";
  m.length = 4.5;
  m.width = 1.8;
  m.height = 1.5;
  for (const Kind& k : kKinds)
    if (category == k.category) {
      m.vclass = k.vclass;
      m.gui_shape = k.shape;
      m.length = k.length;
      m.width = k.width;
      m.height = k.height;
    }
  if (share.length && *share.length > 0) m.length = *share.length;
  if (share.width && *share.width > 0) m.width = *share.width;
  if (share.height && *share.height > 0) m.height = *share.height;
  return m;
}

// The lanes straight on from the end of `lane` (the default continuation, as for entities
// without a route), so that SUMO does not take the vehicle out at its first edge's end.
std::vector<opendrive::LaneEntry> straight_on(const opendrive::RoadNetwork& roads, const std::string& road, int lane) {
  std::vector<opendrive::LaneEntry> out;
  std::set<std::pair<std::string, int>> seen{{road, lane}};
  std::string at = road;
  int on = lane;
  while (out.size() < 64) {
    const auto next = opendrive::straightest_next(roads, at, on);
    if (!next || !seen.insert({next->road_id, next->lane}).second) break;
    out.push_back(*next);
    at = next->road_id;
    on = next->lane;
  }
  return out;
}

double distance(const Vec2& a, const Vec2& b) { return (a - b).norm(); }

}  // namespace

OpenScenarioTraffic::OpenScenarioTraffic(const opendrive::SumoLaneIndex& lanes, long long seed)
    : lanes_(lanes), rng_(static_cast<std::uint64_t>(seed) ^ 0x7472616666696325ULL) {
  const opendrive::RoadNetwork& roads = lanes.roads();
  for (const opendrive::Road& road : roads.roads()) {
    if (road.junction != "-1") continue;  // no spawn in a junction's middle (as esmini's swarm)
    for (double s = kPlaceStep / 2; s < road.length; s += kPlaceStep) {
      const opendrive::LaneSection& section = road.section_at(s);
      for (const auto* side : {&section.right, &section.left})
        for (const opendrive::Lane& lane : *side) {
          if (!moving_traffic_lane(lane.type)) continue;
          const auto sumo = lanes.find(road.id, lane.id, s);
          if (!sumo) continue;
          const opendrive::Pose2 pose = roads.lane_pose(road.id, lane.id, s, 0.0);
          places_.push_back({road.id, lane.id, s, {pose.x, pose.y}, opendrive::travel_heading(road, lane.id, s), *sumo});
        }
    }
  }
}

OpenScenarioTraffic::Tally OpenScenarioTraffic::tally(int serial) const {
  const auto it = tallies_.find(serial);
  return it == tallies_.end() ? Tally{} : it->second;
}

int OpenScenarioTraffic::count(int serial) const {
  return static_cast<int>(std::count_if(vehicles_.begin(), vehicles_.end(),
                                        [&](const auto& v) { return v.second.serial == serial; }));
}

bool OpenScenarioTraffic::free(const Vec2& p, const std::map<std::string, openscenario::EntityState>& entities) const {
  for (const auto& [id, v] : vehicles_)
    if (distance(v.position, p) < kSpacing) return false;
  for (const auto& [name, e] : entities)
    if (e.placed && distance({e.pose.x, e.pose.y}, p) < kSpacing) return false;
  return true;
}

openscenario::TrafficCategoryShare OpenScenarioTraffic::category(
    const std::vector<openscenario::TrafficCategoryShare>& shares) {
  double total = 0;
  for (const auto& s : shares) total += s.weight;
  if (shares.empty() || total <= 0) return {"car", 1.0, {}, {}, {}};
  double u = uniform() * total;
  for (const auto& s : shares) {
    if (u < s.weight) return s;
    u -= s.weight;
  }
  return shares.back();
}

void OpenScenarioTraffic::spawn(int serial, const Place& place, double speed, double max_speed,
                                const openscenario::TrafficCategoryShare& kind, double t, std::vector<sim::Command>& out,
                                const std::set<std::pair<std::string, int>>& keep_on) {
  const std::string id = fmt::format("traffic{}.{}", serial, next_id_++);
  const ModelInfo model = traffic_model(kind);
  std::vector<opendrive::LaneEntry> ahead = straight_on(lanes_.roads(), place.road, place.lane);
  if (!keep_on.empty()) {  // an area's: as far as its lanes go (a junction's lanes only on the way to one of them)
    std::size_t kept = 0;
    for (std::size_t i = 0; i < ahead.size(); ++i) {
      if (keep_on.count({ahead[i].road_id, ahead[i].lane})) kept = i + 1;
      else if (lanes_.roads().road(ahead[i].road_id).junction == "-1") break;
    }
    ahead.resize(kept);
  }
  sim::SpawnVehicle c;
  c.actor = {static_cast<sim::ActorId>(-1), id, ActorKind::Vehicle, model.length, model.width};
  c.model = model;
  c.scripted = false;
  c.traffic = true;
  c.route = opendrive::sumo_route(lanes_, lanes_.roads(), place.road, place.lane, place.s, ahead);
  if (c.route.empty() || c.route.front() != place.sumo.edge) c.route = {place.sumo.edge};
  c.edge = place.sumo.edge;
  c.lane = place.sumo.index;
  c.lane_pos = place.sumo.lane_pos;
  c.speed = speed;
  c.max_speed = max_speed;
  out.push_back(std::move(c));
  vehicles_[id] = {serial, place.point, t, false};
  ++tallies_[serial].spawned;
}

void OpenScenarioTraffic::remove(const std::string& id, int by, std::vector<sim::Command>& out) {
  out.push_back(sim::RemoveActor{id, ActorKind::Vehicle});
  const auto it = vehicles_.find(id);
  const int owner = it == vehicles_.end() ? 0 : it->second.serial;  // 0: a background vehicle
  if (it != vehicles_.end()) {
    Tally& own = tallies_[owner];
    if (by == 0) ++own.not_inserted;
    else ++own.removed;
    vehicles_.erase(it);
  }
  if (by == 0) return;
  ++removed_;
  if (by != owner) {  // a sink's removal (a swarm removes only its own)
    Tally& remover = tallies_[by];
    ++remover.removed;
    if (owner == 0) ++remover.removed_background;
  }
}

std::vector<sim::Command> OpenScenarioTraffic::update(const openscenario::TrafficBook& book,
                                                      const std::map<std::string, openscenario::EntityState>& entities,
                                                      const std::vector<sim::NearbyVehicle>& seen, double t, double dt,
                                                      const std::vector<sim::NearbyVehicle>& background) {
  std::map<std::string, const sim::NearbyVehicle*> now;
  for (const auto& v : seen) now[v.sumo_id] = &v;
  // The background vehicles a sink may take: near an entity, neither an entity nor ours (the
  // ones we spawned are in `seen` or still waiting to be inserted).
  std::vector<const sim::NearbyVehicle*> others;
  for (const auto& v : background)
    if (!now.count(v.sumo_id) && !vehicles_.count(v.sumo_id)) others.push_back(&v);
  removed_background_.clear();
  for (auto it = vehicles_.begin(); it != vehicles_.end();) {
    const auto found = now.find(it->first);
    if (found != now.end()) {
      it->second.position = found->second->position;
      it->second.seen = true;
    } else if (it->second.seen) {  // it left SUMO (its route ended)
      ++tallies_[it->second.serial].left;
      it = vehicles_.erase(it);
      continue;
    }
    ++it;
  }
  std::vector<sim::Command> out;
  // A spawn SUMO could not insert (its place stayed taken) is given up.
  for (auto it = vehicles_.begin(); it != vehicles_.end();) {
    const auto next = std::next(it);
    if (!it->second.seen && t - it->second.spawned > kInsertWait) remove(it->first, 0, out);
    it = next;
  }
  for (const openscenario::Traffic& traffic : book.all()) {
    if (traffic.stopped) continue;
    std::visit(
        [&](const auto& spec) {
          using T = std::decay_t<decltype(spec)>;
          if constexpr (std::is_same_v<T, openscenario::TrafficSwarmAction>) swarm(traffic, spec, entities, t, out);
          else if constexpr (std::is_same_v<T, openscenario::TrafficSourceAction>) source(traffic, spec, entities, t, out);
          else if constexpr (std::is_same_v<T, openscenario::TrafficAreaAction>) area(traffic, spec, entities, t, out);
          else sink(traffic, spec, dt, others, out);
        },
        traffic.spec);
  }
  return out;
}

namespace {

// Where p lies relative to the swarm's ellipse: <= 1 inside (x along the heading).
double ellipse_value(const Vec2& p, const Vec2& centre, double heading, double a, double b) {
  if (a <= 0 || b <= 0) return 2.0;
  const Vec2 d = p - centre;
  const double x = d.x() * std::cos(heading) + d.y() * std::sin(heading);
  const double y = -d.x() * std::sin(heading) + d.y() * std::cos(heading);
  return (x / a) * (x / a) + (y / b) * (y / b);
}

double speed_of(const std::optional<double>& speed, const std::optional<std::pair<double, double>>& range, double u) {
  if (range) return range->first + u * (range->second - range->first);
  return speed.value_or(0.0);
}

}  // namespace

void OpenScenarioTraffic::swarm(const openscenario::Traffic& traffic, const openscenario::TrafficSwarmAction& spec,
                                const std::map<std::string, openscenario::EntityState>& entities, double t,
                                std::vector<sim::Command>& out) {
  const auto central = entities.find(spec.entity);
  if (central == entities.end() || !central->second.placed) return;
  const opendrive::Pose2& pose = central->second.pose;
  const Vec2 centre{pose.x + spec.offset * std::cos(pose.heading), pose.y + spec.offset * std::sin(pose.heading)};
  for (auto it = vehicles_.begin(); it != vehicles_.end();) {
    const auto next = std::next(it);
    if (it->second.serial == traffic.serial && it->second.seen &&
        ellipse_value(it->second.position, centre, pose.heading, spec.semi_major, spec.semi_minor) > 1.0)
      remove(it->first, traffic.serial, out);
    it = next;
  }
  int missing = spec.vehicles - count(traffic.serial);
  if (missing <= 0) return;
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < places_.size(); ++i) {
    const Place& p = places_[i];
    if (distance(p.point, centre) < spec.inner_radius) continue;
    if (ellipse_value(p.point, centre, pose.heading, spec.semi_major, spec.semi_minor) > 1.0) continue;
    candidates.push_back(i);
  }
  while (missing > 0 && !candidates.empty()) {
    const std::size_t k = draw(candidates.size());
    const Place& place = places_[candidates[k]];
    candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(k));
    if (spec.direction_weights) {  // DirectionOfTravelDistribution: this direction's share
      const auto [same, opposite] = *spec.direction_weights;
      const bool along = std::cos(place.heading - pose.heading) >= 0;
      if (uniform() * (same + opposite) >= (along ? same : opposite)) continue;
    }
    if (!free(place.point, entities)) continue;
    const double speed = speed_of(spec.speed, spec.speed_range, uniform());
    spawn(traffic.serial, place, speed, spec.speed || spec.speed_range ? speed : 0.0, category(spec.categories), t,
          out);
    --missing;
  }
}

void OpenScenarioTraffic::source(const openscenario::Traffic& traffic, const openscenario::TrafficSourceAction& spec,
                                 const std::map<std::string, openscenario::EntityState>& entities, double t,
                                 std::vector<sim::Command>& out) {
  if (!traffic.place || spec.rate <= 0) return;
  const Vec2 at{traffic.place->pose.x, traffic.place->pose.y};
  int& spawned = spawned_by_source_[traffic.serial];
  const int due = static_cast<int>(std::floor((t - traffic.started) * spec.rate + 1e-9)) + 1;
  while (spawned < due) {
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < places_.size() && spec.radius > 0; ++i)
      if (distance(places_[i].point, at) <= spec.radius && free(places_[i].point, entities)) candidates.push_back(i);
    std::optional<Place> place;
    if (!candidates.empty()) {
      place = places_[candidates[draw(candidates.size())]];
    } else if (traffic.place->road && traffic.place->lane) {  // on the position's own lane
      const auto& road = *traffic.place->road;
      if (const auto sumo = lanes_.find(road.road_id, *traffic.place->lane, road.s); sumo && free(at, entities)) {
        const opendrive::Road& r = lanes_.roads().road(road.road_id);
        place = Place{road.road_id, *traffic.place->lane, road.s, at,
                      opendrive::travel_heading(r, *traffic.place->lane, road.s), *sumo};
      }
    }
    if (!place) return;  // nowhere free now: due again next step
    const double speed = speed_of(spec.speed, spec.speed_range, uniform());
    spawn(traffic.serial, *place, speed, spec.speed || spec.speed_range ? speed : 0.0, category(spec.categories), t,
          out);
    ++spawned;
  }
}

void OpenScenarioTraffic::area(const openscenario::Traffic& traffic, const openscenario::TrafficAreaAction& spec,
                               const std::map<std::string, openscenario::EntityState>& entities, double t,
                               std::vector<sim::Command>& out) {
  auto found = area_places_.find(traffic.serial);
  if (found == area_places_.end()) {
    std::vector<AreaPlace> points;
    for (const Place& p : places_) points.push_back({p.road, p.lane, p.s, p.point});
    const auto length = [&](const std::string& road) {
      const opendrive::Road* r = lanes_.roads().find(road);
      return r == nullptr ? 0.0 : r->length;
    };
    found = area_places_.emplace(traffic.serial, area_places(points, traffic.polygon, spec.road_ranges, length)).first;
  }
  const std::vector<std::size_t>& mine = found->second;
  // In a road range: beside one of the area's places, less than kAreaHalfWidth across its lane
  // (a lane change onto a lane the range leaves out, or a road alongside, is out) and within
  // kPlaceStep along it (past the range's end is out).
  const auto inside = [&](const Vec2& p) {
    if (traffic.polygon.size() >= 3) return inside_polygon(p, traffic.polygon);
    for (std::size_t i : mine) {
      const Place& place = places_[i];
      const Vec2 d = p - place.point;
      const double along = d.x() * std::cos(place.heading) + d.y() * std::sin(place.heading);
      const double across = -d.x() * std::sin(place.heading) + d.y() * std::cos(place.heading);
      if (std::abs(along) <= kPlaceStep && std::abs(across) <= kAreaHalfWidth) return true;
    }
    return false;
  };
  for (auto it = vehicles_.begin(); it != vehicles_.end();) {
    const auto next = std::next(it);
    if (it->second.serial == traffic.serial && it->second.seen && !inside(it->second.position))
      remove(it->first, traffic.serial, out);
    it = next;
  }
  const Tally& tally = tallies_[traffic.serial];
  int missing = spec.continuous ? spec.entities - count(traffic.serial)
                                : spec.entities - (tally.spawned - tally.not_inserted);
  if (missing <= 0 || mine.empty()) return;
  std::set<std::pair<std::string, int>> lanes;
  for (std::size_t i : mine) lanes.insert({places_[i].road, places_[i].lane});
  std::vector<std::size_t> candidates = mine;
  while (missing > 0 && !candidates.empty()) {
    const std::size_t k = draw(candidates.size());
    const Place& place = places_[candidates[k]];
    candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(k));
    if (!free(place.point, entities)) continue;
    spawn(traffic.serial, place, 0.0, 0.0, category(spec.categories), t, out, lanes);
    --missing;
  }
}

void OpenScenarioTraffic::sink(const openscenario::Traffic& traffic, const openscenario::TrafficSinkAction& spec,
                               double dt, const std::vector<const sim::NearbyVehicle*>& background,
                               std::vector<sim::Command>& out) {
  if (!traffic.place) return;
  const Vec2 at{traffic.place->pose.x, traffic.place->pose.y};
  std::vector<std::string> inside;  // ours first (id order), then the background's (id order)
  for (const auto& [id, v] : vehicles_)
    if (v.seen && distance(v.position, at) <= spec.radius) inside.push_back(id);
  for (const sim::NearbyVehicle* v : background)
    if (!removed_background_.count(v->sumo_id) && distance(v->position, at) <= spec.radius) inside.push_back(v->sumo_id);
  std::size_t n = inside.size();
  if (spec.rate) {
    double& credit = sink_credit_[traffic.serial];
    credit = std::min(credit + *spec.rate * dt, std::max(1.0, *spec.rate * dt));
    n = std::min(n, static_cast<std::size_t>(std::floor(credit + 1e-9)));
    credit -= static_cast<double>(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!vehicles_.count(inside[i])) removed_background_.insert(inside[i]);
    remove(inside[i], traffic.serial, out);
  }
}

TrafficActionRecord traffic_record(const openscenario::Traffic& t, const OpenScenarioTraffic& traffic) {
  TrafficActionRecord r;
  r.kind = std::visit(
      [](const auto& spec) -> std::string {
        using T = std::decay_t<decltype(spec)>;
        if constexpr (std::is_same_v<T, openscenario::TrafficSwarmAction>) return "swarm";
        else if constexpr (std::is_same_v<T, openscenario::TrafficSourceAction>) return "source";
        else if constexpr (std::is_same_v<T, openscenario::TrafficAreaAction>) return "area";
        else return "sink";
      },
      t.spec);
  r.name = t.name;
  r.label = t.name.empty() ? fmt::format("traffic{}", t.serial) : t.name;
  if (r.kind != "sink") r.vehicles = fmt::format("traffic{}.N", t.serial);
  r.started = t.started;
  r.stopped = t.stopped;
  const OpenScenarioTraffic::Tally tally = traffic.tally(t.serial);
  r.spawned = tally.spawned;
  r.removed = tally.removed;
  r.left = tally.left;
  r.not_inserted = tally.not_inserted;
  r.removed_background = tally.removed_background;
  r.active_at_end = traffic.count(t.serial);
  return r;
}

std::string traffic_outcome(const TrafficActionRecord& r) {
  const std::string span =
      fmt::format("{:.2f} s to {}", r.started, r.stopped ? fmt::format("{:.2f} s", *r.stopped) : std::string("the end"));
  if (r.kind == "sink")
    return fmt::format("{} (sink, {}): removed {} vehicles ({} of them background)", r.label, span, r.removed,
                       r.removed_background);
  return fmt::format("{} ({}, {}): {} vehicles spawned, {} removed, {} reached their route's end, {} not inserted, "
                     "{} in SUMO at the end (traffic_actions.csv; SUMO drives them)",
                     r.label, r.kind, span, r.spawned, r.removed, r.left, r.not_inserted, r.active_at_end);
}

}  // namespace orch
