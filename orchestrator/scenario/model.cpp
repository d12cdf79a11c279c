#include "scenario/model.hpp"

namespace orch::scenario {

const char* to_string(Comparison c) {
  switch (c) {
    case Comparison::Greater: return ">";
    case Comparison::GreaterEqual: return ">=";
    case Comparison::Equal: return "=";
    case Comparison::LessEqual: return "<=";
    case Comparison::Less: return "<";
  }
  return "?";
}

}  // namespace orch::scenario
