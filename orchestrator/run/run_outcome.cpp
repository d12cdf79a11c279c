#include "run/run_outcome.hpp"

#include <fmt/format.h>

#include <exception>

#include "core/errors.hpp"

namespace orch {

RunResult new_run_result(const RunRequest& req, Simulator& sim) {
  RunResult result;
  result.step = req.step;
  result.seed = req.seed;
  result.max_time = req.max_time;
  result.backend = sim.backend();
  result.ego_model = req.ego_link ? "plugin" : req.ego_model.name;
  return result;
}

void record_run_error(RunResult& result, RunLog& log) {
  result.verdict = Verdict::Error;
  try {
    throw;
  } catch (const ScenarioError& e) {
    const std::string text = e.what();
    result.reason = fmt::format("invalid scenario: {} error(s); first: {}", e.diagnostics().error_count(),
                                text.substr(0, text.find('\n')));
    for (const auto& d : e.diagnostics().items())
      if (d.severity == Severity::Error) log.note(d.format());
  } catch (const MapError& e) {
    result.reason = std::string("map: ") + e.what();
  } catch (const OrchError& e) {  // SimulationError included
    result.reason = e.what();
  } catch (const std::exception& e) {
    // A bug of ours must still leave a result behind, clearly marked as such.
    result.reason = std::string("internal error: ") + e.what();
  }
}

}  // namespace orch
