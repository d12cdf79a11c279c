#pragma once
// Text of OpenSCENARIO parameter variation files for tests (unit and e2e).
#include <string>

namespace orch::test {

// A Deterministic ParameterValueDistribution over `scenario` with `body` inside Deterministic.
inline std::string deterministic_variation(const std::string& body, const std::string& scenario) {
  return R"(<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" author="t" description="v"/>
  <ParameterValueDistribution>
    <ScenarioFile filepath=")" + scenario + R"("/>
    <Deterministic>
)" + body + R"(
    </Deterministic>
  </ParameterValueDistribution>
</OpenSCENARIO>
)";
}

}  // namespace orch::test
