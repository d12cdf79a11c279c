#include "core/plausible.hpp"

#include <fmt/format.h>

namespace orch {

std::optional<std::string> implausible(double v, Quantity q) {
  const QuantityLimit limit = limit_of(q);
  if (std::isnan(v)) return fmt::format("is not a number (a value in {} is expected)", limit.unit);
  if (std::abs(v) <= limit.max) return std::nullopt;
  return fmt::format("is {:g} {}: its magnitude is beyond {}", v, limit.unit, limit.what);
}

}  // namespace orch
