#pragma once
// The one rule for values a scenario file may hold that no map or run can mean. A reader
// rejects them at `validate` with the key's name; anything within the limits runs (values
// that are merely extreme, such as a 1,000 km offset, reach the engine and behave).
// Why these limits:
// - length 1e7 m (10,000 km): a quarter of the Earth's circumference, far beyond any road
//   network SUMO loads; offsets, distances and positions along a route are lengths.
// - coordinate 1e8 m: projected world coordinates (UTM northings reach 1e7 m, plus false
//   offsets) stay below it.
// - speed 1,000 m/s (3,600 km/h): three times the land speed record; SUMO takes any double,
//   but a vehicle that fast crosses a 10 km map in one step.
// - acceleration 1,000 m/s² (about 100 g): ten times what a crash test pulse reaches.
// - time 1e7 s (about 116 days of simulated time, 2e8 steps of 0.05 s): no run lasts longer.
#include <cmath>
#include <optional>
#include <string>

namespace orch {

enum class Quantity { Length, Coordinate, Speed, SpeedKmh, Acceleration, Time };

struct QuantityLimit {
  double max;        // the largest magnitude accepted, in the file's unit
  const char* unit;  // the file's unit, for messages
  const char* what;  // what the limit stands for, for messages
};

[[nodiscard]] inline QuantityLimit limit_of(Quantity q) {
  switch (q) {
    case Quantity::Length: return {1e7, "m", "10,000 km, more than any map holds"};
    case Quantity::Coordinate: return {1e8, "m", "100,000 km from the origin, beyond any map"};
    case Quantity::Speed: return {1e3, "m/s", "1,000 m/s, faster than anything on a road"};
    case Quantity::SpeedKmh: return {3.6e3, "km/h", "3,600 km/h, faster than anything on a road"};
    case Quantity::Acceleration: return {1e3, "m/s²", "1,000 m/s² (about 100 g)"};
    case Quantity::Time: return {1e7, "s", "10,000,000 s (116 days), longer than any run"};
  }
  return {0, "", ""};
}

// Nullopt when v may be meant; else the reason, e.g. "1e+300 m is beyond 10,000 km, ...".
[[nodiscard]] std::optional<std::string> implausible(double v, Quantity q);

}  // namespace orch
