#pragma once
// The batch's metrics.csv (docs/evaluation.md "Batches"): one row per run, the table a test
// engineer loads into a notebook to see where in the parameter space the stack becomes
// critical. Columns: run_id, logical_uuid, parameter_uuid, seed, verdict, then every
// parameter (`group.name`), every criterion (`criterion.<name>.actual`, `.success`) and every
// metric summary value (`metrics.<actor>.<key>`) any run has, and `preventable` when a run
// had a reference run (docs/reference-driver.md), sorted by name; empty cells
// where a run has none (a missing run has only its ids and verdict "missing").
#include <string>

#include "batch/batch_report.hpp"

namespace orch::batch {

std::string batch_metrics_csv(const BatchReport& report);

}  // namespace orch::batch
