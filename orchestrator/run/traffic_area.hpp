#pragma once
// Where a TrafficAreaAction's (1.3) vehicles may be (pure): the road places of its area.
//   Polygon    the places inside the polygon (its corners as resolved when the action started;
//              even-odd rule, so a self-crossing polygon is what its outline encloses).
//   RoadRange  from each RoadCursor to the next: on the same road the s between them; on
//              another road, the first road from its cursor's s to its end and the next from
//              its start to its cursor's s (a cursor without s: the whole road on that side).
//              A cursor's Lanes limit its part (none: every lane; the first cursor's lanes for a
//              part on one road, else the part's own cursor's). `length` ends the range that
//              many metres after its first cursor, counted along the parts in order.
// Junctions' connecting roads hold no places (as for every TrafficAction), so a range or a
// polygon over a junction spawns nothing in its middle; its vehicles drive through it.
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/polyline.hpp"
#include "openscenario/traffic_model.hpp"

namespace orch {


// A place as the area test needs it (OpenScenarioTraffic::Place has more).
struct AreaPlace {
  std::string road;
  int lane = 0;
  double s = 0;
  Vec2 point{0, 0};
};

// Indices into `places` of those in the area: in `polygon` when it has corners, else in
// `ranges`. `road_length` gives a road's length (0: no such road, its cursors cover nothing).
template <class LengthOf>
std::vector<std::size_t> area_places(const std::vector<AreaPlace>& places, const std::vector<Vec2>& polygon,
                                     const std::vector<openscenario::TrafficAreaRoadRange>& ranges,
                                     LengthOf road_length);

// ---- implementation -----------------------------------------------------------------

struct AreaPart {
  std::string road;
  double from = 0, to = 0;  // s interval
  std::vector<int> lanes;   // empty: every lane
};
std::vector<AreaPart> area_parts(const openscenario::TrafficAreaRoadRange& range,
                                 const std::vector<double>& cursor_road_lengths);
bool in_parts(const AreaPlace& place, const std::vector<AreaPart>& parts);

template <class LengthOf>
std::vector<std::size_t> area_places(const std::vector<AreaPlace>& places, const std::vector<Vec2>& polygon,
                                     const std::vector<openscenario::TrafficAreaRoadRange>& ranges,
                                     LengthOf road_length) {
  std::vector<AreaPart> parts;
  for (const auto& range : ranges) {
    std::vector<double> lengths;
    for (const auto& c : range.cursors) lengths.push_back(road_length(c.road));
    for (AreaPart& p : area_parts(range, lengths)) parts.push_back(std::move(p));
  }
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < places.size(); ++i)
    if (polygon.size() >= 3 ? inside_polygon(places[i].point, polygon) : in_parts(places[i], parts)) out.push_back(i);
  return out;
}

}  // namespace orch
