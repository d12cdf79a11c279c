#pragma once
// Which scenario language a file is written in, decided in this one place by the file's
// content (the extension only when the content says nothing): ScenarioExecutor JSON starts
// with '{', OpenSCENARIO XML has the root element OpenSCENARIO.
#include <string>

namespace orch {

enum class ScenarioFormat { ScenarioExecutorJson, OpenScenario, Unknown };

ScenarioFormat detect_scenario_format(const std::string& path);

}  // namespace orch
