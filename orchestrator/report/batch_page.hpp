#pragma once
// report.html of a batch folder (README "Looking at results"): built from the same files as
// summary.json (batch.json, the execution traces) plus each run's result.json and bound
// scenario, so a merge of shards gets the same report as a batch run on one machine.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "batch/batch_report.hpp"

namespace orch::report {

// The data the page draws: totals, logical scenarios (their parameters and scene graph),
// every finished run (verdict, values, scenes visited, metric summary, its report).
nlohmann::json batch_report_data(const batch::BatchReport& report, const std::filesystem::path& out_dir);

// Writes `out_dir`/report.html atomically and returns its path.
std::filesystem::path write_batch_report(const batch::BatchReport& report, const std::filesystem::path& out_dir);

}  // namespace orch::report
