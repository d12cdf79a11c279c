// Position: the seven kinds the orchestrator resolves on OpenDRIVE roads.
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

std::optional<Orientation> read_orientation(Element& owner) {
  auto element = owner.optional_child("Orientation");
  if (!element) return std::nullopt;
  Orientation o;
  o.relative = element->optional_choice<bool>("type", {{"relative", true}, {"absolute", false}}).value_or(true);
  o.h = element->optional_number("h").value_or(0.0);
  // Pitch and roll are read (they must be numbers) but not used: positions are resolved in
  // the road plane (x, y, heading); a road's elevation and superelevation give them where
  // the map resolves z, pitch and roll (docs/openscenario.md).
  for (const char* angle : {"p", "r"}) (void)element->optional_number(angle);
  element->finish();
  return o;
}

Position read_kind(Element& p) {
  const std::string_view kind = p.name();
  if (kind == "WorldPosition") {
    WorldPosition w{p.number("x"), p.number("y"), p.optional_number("h")};
    p.ignore_attributes({"z", "p", "r"});
    return w;
  }
  if (kind == "RelativeWorldPosition") {
    p.ignore_attributes({"dz"});
    return RelativeWorldPosition{p.text("entityRef"), p.number("dx"), p.number("dy"), read_orientation(p)};
  }
  if (kind == "RelativeObjectPosition") {
    p.ignore_attributes({"dz"});
    return RelativeObjectPosition{p.text("entityRef"), p.number("dx"), p.number("dy"), read_orientation(p)};
  }
  if (kind == "RoadPosition")
    return RoadPosition{p.text("roadId"), p.number("s"), p.number("t"), read_orientation(p)};
  if (kind == "RelativeRoadPosition")
    return RelativeRoadPosition{p.text("entityRef"), p.number("ds"), p.number("dt"), read_orientation(p)};
  if (kind == "LanePosition")
    return LanePosition{p.text("roadId"), p.integer("laneId"), p.number("s"), p.optional_number("offset").value_or(0.0),
                        read_orientation(p)};
  // RelativeLanePosition: ds or dsLane (1.1+); only ds is run.
  RelativeLanePosition r{p.text("entityRef"), p.integer("dLane"), p.number("ds"),
                         p.optional_number("offset").value_or(0.0), read_orientation(p)};
  if (p.has("dsLane")) p.fail_attribute("dsLane", "dsLane is not supported (use ds)");
  return r;
}

}  // namespace

Position read_position(Element& position) {
  Element p = position.one_of({"WorldPosition", "RelativeWorldPosition", "RelativeObjectPosition", "RoadPosition",
                               "RelativeRoadPosition", "LanePosition", "RelativeLanePosition"});
  position.finish();
  Position result = read_kind(p);
  p.finish();
  return result;
}

}  // namespace orch::openscenario::reading
