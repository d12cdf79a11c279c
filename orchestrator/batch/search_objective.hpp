#pragma once
// What `orchestrator search` reads from a run's result.json: the objective it minimises (or
// colours the runs by) and the pass/fail outcome whose boundary it looks for.
//  objective: "sim_time", "METRIC" (the ego's summary of a metric, e.g. min_ttc), "ACTOR.METRIC"
//             (e.g. LeadVehicle.max_decel), or "criterion:NAME" (the criterion's actual value);
//  boundary:  "verdict" (success passes), "collision" (none passes), or a criterion's name.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace orch::batch {

// The metric summaries result.json has per actor (min_ttc, min_gap, max_decel, ...).
std::vector<std::string> objective_metric_names();
// Throws OrchError for an objective naming no known metric (did you mean).
void check_objective(const std::string& objective);
// The objective's value in one result; nullopt when the run has none (never closing: no TTC).
// Throws OrchError for an actor or criterion the result does not have (did you mean).
std::optional<double> objective_value(const nlohmann::json& result, const std::string& objective);
// Whether the run passed `criterion`. Throws OrchError for a criterion the result does not
// name (did you mean, among verdict, collision and its criteria).
bool criterion_passed(const nlohmann::json& result, const std::string& criterion);

}  // namespace orch::batch
