#pragma once
// `orchestrator validate` for OpenSCENARIO files: loads the scenario (xosc_reader.hpp), reads
// its OpenDRIVE road and checks that every absolute road and lane position exists there.
#include <string>

#include "core/diagnostics.hpp"
#include "openscenario/xosc_reader.hpp"

namespace orch::openscenario {

Diagnostics check_scenario_file(const std::string& path, const LoadOptions& options = {});

}  // namespace orch::openscenario
