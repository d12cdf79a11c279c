#pragma once
// The only ways the code turns a coordinate, distance, time or count held in a double into an
// integer. A value read from a file can be anything a double holds (1e300, inf, NaN), and
// converting a double that does not fit to an integer type is undefined behaviour in C++
// (and std::lround of such a value is unspecified). Every such conversion goes through
// these: they say "does not fit" (nullopt) or clamp into a stated range, never overflow.
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace orch {

// Every integer of magnitude up to 2^53 is exact in a double, and ±2^53 fits every 64-bit
// integer type with room to add to it: the range in which a floored double is an index.
inline constexpr double kExactIntegerLimit = 9007199254740992.0;

// floor(v) as an integer, or nullopt when v is NaN, infinite or beyond ±2^53.
[[nodiscard]] inline std::optional<long long> floor_to_integer(double v) {
  if (!(std::abs(v) <= kExactIntegerLimit)) return std::nullopt;  // NaN fails every comparison
  return static_cast<long long>(std::floor(v));
}

namespace detail {
template <class Int>
[[nodiscard]] Int clamp_integral(double v, Int lo, Int hi) {
  static_assert(std::is_integral_v<Int>);
  if (std::isnan(v)) return lo;
  // Compared as doubles: lo and hi are exact in a double when they are within ±2^53, and a
  // rounded hi (2^63 - 1 becomes 2^63) is caught by >= before the conversion.
  if (v <= static_cast<double>(lo)) return lo;
  if (v >= static_cast<double>(hi)) return hi;
  return static_cast<Int>(v);
}
}  // namespace detail

// Spatial grids index coordinates within ±1e12 m: far beyond any map (core/plausible.hpp),
// and cell indices then stay far inside a 64-bit key (cx * 4000037 + cy).
inline constexpr double kGridReach = 1e12;

// The grid cell of coordinate v for cells of `cell` m (cell >= 1 m): a coordinate beyond
// the reach lands in the edge cell and NaN in cell 0, so a bad value costs a wrong
// neighbour test (every user checks real distances after), never an overflow.
[[nodiscard]] inline long long grid_cell(double v, double cell) {
  const double bounded = std::isnan(v) ? 0.0 : std::min(std::max(v, -kGridReach), kGridReach);
  return static_cast<long long>(std::floor(bounded / cell));
}

// std::floor / std::ceil / std::round of v, clamped into [lo, hi]; NaN gives lo.
template <class Int>
[[nodiscard]] Int clamped_floor(double v, Int lo, Int hi) {
  return detail::clamp_integral(std::floor(v), lo, hi);
}
template <class Int>
[[nodiscard]] Int clamped_ceil(double v, Int lo, Int hi) {
  return detail::clamp_integral(std::ceil(v), lo, hi);
}
template <class Int>
[[nodiscard]] Int clamped_round(double v, Int lo, Int hi) {
  return detail::clamp_integral(std::round(v), lo, hi);
}

// The number of pieces of `step` that cover `length` (at least `minimum`, at most `maximum`):
// how sampled geometry sizes its arrays. A NaN or infinite length gives `minimum`, a huge one
// `maximum`, so a bad value costs bounded memory and time instead of an overflow.
[[nodiscard]] inline int pieces_covering(double length, double step, int minimum, int maximum) {
  if (!std::isfinite(length) || !(step > 0)) return minimum;
  return clamped_ceil<int>(length / step, minimum, maximum);
}

}  // namespace orch
