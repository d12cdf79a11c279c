#pragma once
// A number that is the whole of a text ("3.5", "-4"; not "3.5 m", not "nan").
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

namespace orch::openscenario {

template <class T>
std::optional<T> parse_whole(std::string_view text) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>)
    if (!std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace orch::openscenario
