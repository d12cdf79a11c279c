#pragma once
// Element names of the OpenSCENARIO 1.0-1.3 schema. An element found where the orchestrator
// does not read it is reported as "not supported" when it is one of these, and as unknown
// (with "did you mean") when it is not: misspellings and unsupported features never pass
// silently.
#include <string_view>

namespace orch::openscenario {

bool is_standard_element(std::string_view name);

}  // namespace orch::openscenario
