#pragma once
// Which model drives the ego (run --ego-model, the evaluation file's EgoModel, an
// OpenSCENARIO controller named so): SUMO's car-following model ("sumo", the default) or
// the UN R157 reference driver ("r157", with optional parameter overrides).
#include <map>
#include <string>
#include <vector>

namespace orch {

struct EgoModelChoice {
  std::string name = "sumo";
  std::map<std::string, double> parameters;  // r157 only (reference_driver/r157_parameters.hpp)

  [[nodiscard]] bool r157() const { return name == "r157"; }
};

inline const std::vector<std::string>& ego_model_names() {
  static const std::vector<std::string> names{"sumo", "r157"};
  return names;
}

// The name of the OpenSCENARIO controller that asks for the reference driver.
inline constexpr const char* kR157ControllerName = "R157ReferenceDriver";

}  // namespace orch
