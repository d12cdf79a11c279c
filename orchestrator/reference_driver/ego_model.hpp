#pragma once
// Which model drives the ego (run --ego-model, the evaluation file's EgoModel, an
// OpenSCENARIO controller named so): SUMO's car-following model ("sumo", the default), the
// UN R157 reference driver ("r157", with optional parameter overrides), or "cruise": an ego
// that keeps its set speed and lane and brakes for nothing, the stand-in for a system under
// test that does not react (what a reference run judges as preventable or not).
#include <map>
#include <string>
#include <vector>

namespace orch {

struct EgoModelChoice {
  std::string name = "sumo";
  std::map<std::string, double> parameters;  // r157 only (reference_driver/r157_parameters.hpp)

  [[nodiscard]] bool r157() const { return name == "r157"; }
  [[nodiscard]] bool cruise() const { return name == "cruise"; }
  // The orchestrator's own driver model drives the ego (reference_driver::ReferenceEgo), not SUMO.
  [[nodiscard]] bool own_model() const { return r157() || cruise(); }
};

inline const std::vector<std::string>& ego_model_names() {
  static const std::vector<std::string> names{"sumo", "r157", "cruise"};
  return names;
}

// The name of the OpenSCENARIO controller that asks for the reference driver.
inline constexpr const char* kR157ControllerName = "R157ReferenceDriver";

}  // namespace orch
