#include "run/same_commands.hpp"

#include <cstring>
#include <tuple>

namespace orch {

namespace {

// Doubles compared by their bits; everything else by ==. A field added to a command and not
// listed here makes runs share SUMO when they should not: each struct's fields are listed
// in the order of sim/world.hpp, and tests/unit/test_same_commands.cpp changes each one.
struct Bits {
  double v;
  bool operator==(const Bits& o) const { return std::memcmp(&v, &o.v, sizeof v) == 0; }
};
Bits bits(double v) { return {v}; }
auto vec(const Vec2& p) { return std::make_tuple(bits(p.x()), bits(p.y())); }

auto fields(const sim::TrackedActor& a) { return std::make_tuple(a.id, a.sumo_id, a.kind, bits(a.length), bits(a.width)); }
auto fields(const ModelInfo& m) {
  return std::make_tuple(m.id, m.kind, bits(m.length), bits(m.width), bits(m.height), m.vclass, m.gui_shape, m.emergency);
}
auto fields(const sim::SpawnVehicle& c) {
  return std::make_tuple(fields(c.actor), fields(c.model), c.color, c.scripted, c.route, c.edge, c.lane, bits(c.lane_pos),
                         bits(c.speed), bits(c.max_speed), c.keep_lateral, c.traffic);
}
auto fields(const sim::SpawnPerson& c) {
  return std::make_tuple(fields(c.actor), fields(c.model), c.color, c.edge, bits(c.lane_pos));
}
auto fields(const sim::SetPose& c) {
  return std::make_tuple(c.sumo_id, c.kind, bits(c.length), vec(c.position), bits(c.heading), bits(c.speed), c.edge, c.lane,
                         c.signals, c.scripted, c.centred);
}
auto fields(const sim::SetSignals& c) { return std::make_tuple(c.sumo_id, c.signals); }
auto fields(const sim::SetMaxSpeed& c) { return std::make_tuple(c.sumo_id, bits(c.speed)); }
auto fields(const sim::SetStop& c) { return std::make_tuple(c.sumo_id, c.edge, c.lane, bits(c.lane_pos), bits(c.length)); }
auto fields(const sim::SetParameter& c) { return std::make_tuple(c.sumo_id, c.key, c.value); }
auto fields(const sim::RemoveActor& c) { return std::make_tuple(c.sumo_id, c.kind); }
auto fields(const sim::ReleaseActor& c) { return std::make_tuple(c.sumo_id, bits(c.max_speed)); }
auto fields(const sim::SetRoute& c) { return std::make_tuple(c.sumo_id, c.edges); }
auto fields(const sim::SetTrafficLight& c) { return std::make_tuple(c.tls_id, c.links); }
auto fields(const sim::DriveSpeed& c) { return std::make_tuple(c.sumo_id, bits(c.speed)); }

bool same(const sim::Command& a, const sim::Command& b) {
  if (a.index() != b.index()) return false;
  return std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        return fields(x) == fields(std::get<T>(b));
      },
      a);
}

}  // namespace

bool same_commands(const std::vector<sim::Command>& a, const std::vector<sim::Command>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

bool same_tracked(const std::vector<sim::TrackedActor>& a, const std::vector<sim::TrackedActor>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (fields(a[i]) != fields(b[i])) return false;
  return true;
}

}  // namespace orch
