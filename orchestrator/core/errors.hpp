#pragma once
// The project's error types. Each run catches them in one place and turns them into a
// verdict: bad input and broken infrastructure are `error`, never a test `failure`.
#include <stdexcept>
#include <string>

#include "core/diagnostics.hpp"

namespace orch {

class OrchError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad scenario input: carries every problem found, each with file, line and JSON pointer.
class ScenarioError : public OrchError {
 public:
  explicit ScenarioError(Diagnostics diagnostics)
      : OrchError(diagnostics.format()), diagnostics_(std::move(diagnostics)) {}
  ScenarioError(SourceLocation where, const std::string& message)
      : ScenarioError(single(std::move(where), message)) {}
  [[nodiscard]] const Diagnostics& diagnostics() const { return diagnostics_; }

 private:
  static Diagnostics single(SourceLocation where, const std::string& message) {
    Diagnostics d;
    d.error(std::move(where), message);
    return d;
  }
  Diagnostics diagnostics_;
};

// A map that cannot be found, built or read (waypoint file, map.json, SUMO net).
class MapError : public OrchError {
 public:
  using OrchError::OrchError;
};

// SUMO refused or failed (bad net, TraCI exception, process died).
class SimulationError : public OrchError {
 public:
  using OrchError::OrchError;
};

}  // namespace orch
