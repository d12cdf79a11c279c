#pragma once
// Placing scripted vehicles in SUMO: moveToXY made safe (move_to_xy), the accelerations of
// placed vehicles (Placements::placed_accelerations), and
// which keepRoute a scripted vehicle's moveToXY gets (lane_fit.hpp says why it matters).
// keepRoute 2 (free placement) is what every pose had; it makes SUMO weigh every lane near the
// point, whole shapes, every step. keepRoute 3 (along the route, may leave the net) looks at the
// lanes of the vehicle's route only and takes the hinted lane when the point lies on it; it is
// used when both must give the same placement:
//   - the vehicle's route in SUMO is exactly the hinted edge: a scripted vehicle departs on a
//     route of its first edge, and after a free placement SUMO's route is whatever that match
//     made it (read back once, before the next fast placement is considered);
//   - the front lies well inside the hinted lane (front_fits_lane: near its centre line, not
//     at its ends, heading along it when no other lane of the edge lets the vehicle's class
//     drive), and the lane lets the
//     vehicle's class drive on it (SUMO's free match skips lanes that do not).
// Then both matches pick the hinted lane, the same lane position (the nearest point of its
// shape) and the same lateral offset, and neither changes the route: the trace is byte for byte
// the same (docs/performance.md, "SUMO placing the scripted cars").
//
// Included by sumo_simulator.cpp only (compiled once per SUMO client library).
#include <algorithm>
#include <cstring>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "lane_fit.hpp"
#include "sim/world.hpp"
#include "sumo_api.hpp"

namespace orch::sumo_placing {
namespace {  // compiled once per client library, like sumo_reader.hpp

namespace sumo = orch_sumo;

#ifndef LIBTRACI
// Not instrumented: under AddressSanitizer the buffer must be on the real stack too.
[[gnu::noinline]] __attribute__((no_sanitize("address"))) inline void clear_stack_below() {
  char pad[16384];
  std::memset(pad, 0, sizeof pad);
  asm volatile("" : : "r"(pad) : "memory");  // the stores must happen
}
#endif

// SUMO 1.15's Vehicle::moveToXY leaves its local `lanePos` unset when the point matches no
// lane (beyond a dead end, far off the road: a placement off the network, which a scripted
// entity may need) and then asserts that it is not NaN; Debian's build keeps assertions, so
// whether such a run aborted depended on what earlier calls had left on the stack (it did in
// the CI's unity build). In-process that local lies in the stack just below this frame:
// zeroing that stack first makes the read a 0, every time. On the traci backend the read
// happens in the sumo process, on a stack of its own that this build does not change.
inline void move_to_xy(const std::string& id, const std::string& edge, int lane, const Vec2& front, double angle,
                       int keep_route) {
#ifndef LIBTRACI
  clear_stack_below();
#endif
  sumo::Vehicle::moveToXY(id, edge, lane, front.x(), front.y(), angle, keep_route);
}

class Placements {
 public:
  // A vehicle the orchestrator places has the speeds it is given, one per step; SUMO's own
  // acceleration of it is the change from the speed SUMO had at the start of the step, which
  // SUMO itself may have changed in between (an emergency stop at a dead end it was placed
  // beyond reads as 200 m/s^2 the next step). Its acceleration is the change of the speeds
  // read, computed as SUMO computes it (the same double wherever SUMO did not interfere).
  void placed_accelerations(const std::vector<sim::TrackedActor>& actors, sim::WorldSnapshot& snap, double step) {
    for (std::size_t i = 0; i < actors.size() && i < snap.actors.size(); ++i) {
      sim::ActorState& a = snap.actors[i];
      const auto it = vehicles_.find(actors[i].sumo_id);
      if (!a.present || actors[i].kind == ActorKind::Pedestrian || it == vehicles_.end()) continue;
      if (it->second.speed_read) a.accel = (a.speed - *it->second.speed_read) / step;
      it->second.speed_read = a.speed;
    }
  }

  // A scripted vehicle departs: on a route of one edge it may take the fast placement.
  void spawned(const std::string& id, const std::vector<std::string>& route, const std::string& vclass) {
    Vehicle& v = vehicles_[id];
    v = Vehicle{};
    v.eligible = route.size() == 1;
    if (v.eligible) v.route_edge = route.front();
    v.vclass = vclass;
  }
  void forget(const std::string& id) { vehicles_.erase(id); }

  // keepRoute for the pose of vehicle `id` with front `front` on hinted lane (edge, lane).
  int keep_route(const std::string& id, const std::string& edge, int lane, const Vec2& front, double heading) {
    const auto it = vehicles_.find(id);
    if (it == vehicles_.end() || !it->second.eligible || edge.empty()) return kFree;
    Vehicle& v = it->second;
    // The first pose inserts the vehicle: SUMO's two matches treat a vehicle not yet on the
    // road differently, so it is placed freely.
    if (!v.departed) {
      v.departed = true;
      return placed_freely(v);
    }
    if (v.hint == nullptr || edge != v.hint_edge || lane != v.hint_lane) hint(v, edge, lane);
    const Lane& shape = *v.hint;
    if (!shape.allows(v.vclass)) return placed_freely(v);
    if (!front_fits_lane(shape.centre, shape.width, v.usable_lanes, front, heading)) return placed_freely(v);
    if (!v.route_known) {
      // One query (a round trip on the traci backend); after one that does not allow the
      // fast placement, the next waits a while: placing freely is always right, only slower.
      if (v.wait > 0) {
        --v.wait;
        return kFree;
      }
      const std::vector<std::string> route = sumo::Vehicle::getRoute(id);
      v.route_edge = route.size() == 1 ? std::optional<std::string>(route.front()) : std::nullopt;
      v.route_known = true;
      if (v.route_edge != edge) {
        v.wait = kQueryPause;
        return placed_freely(v);
      }
    }
    // Another edge than the route's: placed freely (the route is read again before the next).
    if (v.route_edge != edge) return placed_freely(v);
    return kAlongRoute;
  }

 private:
  static constexpr int kFree = 2;        // may leave the route and the network
  static constexpr int kAlongRoute = 3;  // along the route, may leave the network
  static constexpr int kQueryPause = 20;  // poses placed freely before the route is read again

  struct Lane;
  struct Vehicle {
    bool eligible = false;
    bool departed = false;
    bool route_known = true;
    int wait = 0;  // poses before the route may be read again
    std::optional<std::string> route_edge;  // the route's only edge
    std::string vclass;
    std::optional<double> speed_read;  // the last speed read (placed_accelerations)
    // The hinted lane of the last pose and how many lanes of its edge the vehicle's class may
    // use (only those are candidates of the free match): looked up when the hint changes,
    // not every step.
    std::string hint_edge;
    int hint_lane = -1;
    const Lane* hint = nullptr;
    int usable_lanes = 0;
  };
  struct Lane {
    Polyline centre;
    double width = 0;
    int edge_lanes = 1;
    std::vector<std::string> allowed;  // empty: every class
    [[nodiscard]] bool allows(const std::string& vclass) const {
      return allowed.empty() || std::find(allowed.begin(), allowed.end(), vclass) != allowed.end();
    }
  };

  void hint(Vehicle& v, const std::string& edge, int lane) {
    v.hint_edge = edge;
    v.hint_lane = lane;
    v.hint = &lane_of(edge + "_" + std::to_string(lane));  // the map's nodes never move
    v.usable_lanes = 0;
    for (int i = 0; i < v.hint->edge_lanes; ++i)
      if (lane_of(edge + "_" + std::to_string(i)).allows(v.vclass)) ++v.usable_lanes;
  }

  // A free placement may change the route: read it again before the next fast one.
  static int placed_freely(Vehicle& v) {
    v.route_known = false;
    return kFree;
  }

  const Lane& lane_of(const std::string& lane_id) {
    auto it = lanes_.find(lane_id);
    if (it != lanes_.end()) return it->second;
    Lane l;
    std::vector<Vec2> points;
    for (const auto& p : sumo::Lane::getShape(lane_id).value) points.emplace_back(p.x, p.y);
    l.centre = Polyline(std::move(points));
    l.width = sumo::Lane::getWidth(lane_id);
    l.edge_lanes = sumo::Edge::getLaneNumber(sumo::Lane::getEdgeID(lane_id));
    l.allowed = sumo::Lane::getAllowed(lane_id);
    return lanes_.emplace(lane_id, std::move(l)).first->second;
  }

  std::unordered_map<std::string, Vehicle> vehicles_;
  std::unordered_map<std::string, Lane> lanes_;  // shapes never change during a run
};

}  // namespace
}  // namespace orch::sumo_placing
