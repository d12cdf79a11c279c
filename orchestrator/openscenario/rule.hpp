#pragma once
// The standard's comparison rules (ValueConstraint, conditions): `value rule bound`.
#include "openscenario/model.hpp"

namespace orch::openscenario {

template <class T>
bool satisfies(Rule rule, const T& value, const T& bound) {
  switch (rule) {
    case Rule::EqualTo: return value == bound;
    case Rule::NotEqualTo: return !(value == bound);
    case Rule::GreaterThan: return bound < value;
    case Rule::LessThan: return value < bound;
    case Rule::GreaterOrEqual: return !(value < bound);
    case Rule::LessOrEqual: return !(bound < value);
  }
  return false;
}

}  // namespace orch::openscenario
