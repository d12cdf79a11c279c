#pragma once
// How one criterion came out (result.json "criteria", as scenario_runner's JSON lists them).
#include <optional>
#include <string>

#include "sim/actor.hpp"

namespace orch::criteria {

struct CriterionResult {
  std::string name;
  std::optional<sim::ActorId> actor;
  std::string metric;    // the metric judged ("collisions", "scene" for the built-ins that are not metrics)
  std::string expected;  // the limit in words: "ttc >= 2 at every step", ...
  std::optional<double> actual;  // the measured value that decided (none: never measured)
  std::optional<double> at_time;  // s, when it was measured (the worst step, the first violation, ...)
  bool success = false;
};

}  // namespace orch::criteria
