#pragma once
// Loads an OpenSCENARIO 1.0-1.3 scenario file (.xosc) into plain values (model.hpp):
// parameters with --param overrides and constraint checks, catalogs, entities, the road
// file and the storyboard. Throws ScenarioError naming file, line and element path.
#include <map>
#include <string>
#include <vector>

#include "openscenario/model.hpp"

namespace orch::openscenario {

struct LoadOptions {
  // --param NAME=VALUE: replaces a declared parameter's value before anything uses it.
  std::map<std::string, std::string> parameter_overrides;
};

// "NAME=VALUE" texts of --param into overrides; throws OrchError for a text without '='
// or a name given twice.
std::map<std::string, std::string> parse_parameter_overrides(const std::vector<std::string>& texts);

Scenario load_scenario(const std::string& path, const LoadOptions& options = {});

}  // namespace orch::openscenario
