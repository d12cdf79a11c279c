#pragma once
// The SUMO lanes under the waypoint routes, computed once per map: every waypoint of every
// route resolves to edge, lane, lane position (SUMO's lane coordinates) and lateral offset,
// respecting the direction of travel. Routes are tied to lanes through the lane parameter
// "orch.route" that `map build` writes into the net.
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/polyline.hpp"
#include "map/waypoint_file.hpp"

namespace orch {

struct LaneInfo {
  std::string id;    // SUMO lane id, e.g. "Waypoint03+Waypoint02+Waypoint01#0_1" (net_plan.hpp)
  std::string edge;  // SUMO edge id
  int index = 0;     // 0 = rightmost
  double length = 0; // SUMO lane length (lane positions run 0..length)
  double width = 0;
  double speed = 0;  // m/s
  Polyline shape;
  std::vector<std::string> routes;  // waypoint routes this lane was built from
  bool internal = false;            // a lane inside a junction (SUMO's ":<node>_<n>_<i>")
  std::vector<int> next;            // lanes a vehicle on this lane continues on (via connections)

  // SUMO scales positions on lanes whose drawn shape is longer or shorter than the lane.
  [[nodiscard]] double geometry_factor() const { return shape.length() / length; }
};

struct LanePlace {
  int lane = -1;          // index into LaneMap::lanes()
  double lane_pos = 0;    // SUMO lane position, m
  double lateral = 0;     // m from the lane centre, + = left
  double distance = 0;    // |lateral| unless the point lies beyond the lane's ends
};

struct RouteLanes {
  std::string route_id;
  // The lanes that drive the route, in driving order, internal lanes through junctions
  // included; a lane appears again where the route drives it again (a loop).
  std::vector<int> lanes;
  std::vector<LanePlace> points;   // one per waypoint
  std::vector<int> visits;         // per waypoint: its position in `lanes`
};

class LaneMap {
 public:
  // Parses the SUMO net (pugixml) and maps every waypoint. Throws MapError when a route has
  // no lanes in the net (the net was not built from this waypoint file), or when its lanes
  // do not connect into one path along it (naming the waypoint where the path breaks).
  static LaneMap build(const std::string& net_file, const WaypointFile& waypoints);

  [[nodiscard]] const std::vector<LaneInfo>& lanes() const { return lanes_; }
  [[nodiscard]] const LaneInfo& lane(int i) const { return lanes_[static_cast<std::size_t>(i)]; }
  [[nodiscard]] const RouteLanes* route(std::string_view route_id) const;

  // Where a point at arc length s of a route, `lateral` metres left of it, lies on the
  // route's own lanes (the lane nearest to it among them). Interpolates between the
  // precomputed places of the neighbouring waypoints; s beyond the route extends it
  // straight (the lanes reach lane_extension past the end waypoints). Throws MapError for a
  // route this map does not know.
  [[nodiscard]] LanePlace place_on_route(const WaypointRoute& route, double s, double lateral) const;
  // place_on_route moved off a junction interior (SUMO inserts and stops vehicles on normal
  // lanes only): to the start of the next normal lane along the route (forward) or the end
  // of the previous one. Unchanged when it already lies on a normal lane.
  [[nodiscard]] LanePlace normal_place_on_route(const WaypointRoute& route, double s, double lateral,
                                                bool forward) const;
  // Nearest lane whose direction is within 90 degrees of `heading`; nullopt if none within
  // `max_distance` metres.
  [[nodiscard]] std::optional<LanePlace> locate(const Vec2& p, double heading, double max_distance = 10.0) const;
  // SUMO edges a vehicle passes driving route `route_id` from arc length s0 to s1, in
  // driving order, each once (s1 < s0 is read as the stretch between them).
  [[nodiscard]] std::vector<std::string> route_edges(const WaypointRoute& route, double s0, double s1) const;
  // Convert a point on a lane into SUMO lane coordinates (lane_pos clamped to the lane).
  [[nodiscard]] LanePlace place_on_lane(int lane, const Vec2& p) const;

 private:
  struct Bounds {
    Vec2 lo;
    Vec2 hi;
  };
  [[nodiscard]] const RouteLanes& route_or_throw(const WaypointRoute& route) const;
  // The lane of `candidates` nearest to p, preferring lanes beside which p lies.
  // `first`: a lane likely to be the answer (e.g. the previous waypoint's), tried before the
  // others so that the bounding-box test skips the rest cheaply.
  [[nodiscard]] LanePlace nearest_of(const std::vector<int>& candidates, const Vec2& p, int first = -1) const;
  // Junction maps: follows the route through the lane graph, waypoint by waypoint (lane_walk.cpp).
  [[nodiscard]] RouteLanes walk(const WaypointRoute& route, const std::string& net_file) const;
  // The visit (index into rl.lanes) of arc length s of the route.
  [[nodiscard]] int visit_at(const WaypointRoute& route, const RouteLanes& rl, double s) const;

  std::vector<LaneInfo> lanes_;
  std::vector<Bounds> bounds_;  // per lane, for skipping far lanes cheaply
  std::unordered_map<std::string, RouteLanes> routes_;
  bool junctions_ = false;  // the net has junction interiors the routes drive (internal lanes)
};

}  // namespace orch
