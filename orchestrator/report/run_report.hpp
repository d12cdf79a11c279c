#pragma once
// report.html of one run folder (README "Looking at results"): built from the run's files
// alone (result.json, trace.csv, metrics.csv, background.csv, run.log and the SUMO net the
// result names), so it can be written at the end of a run or again later for any run.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "results/run_files.hpp"

namespace orch::report {

// The data the page draws. Problems with optional files (a malformed trace, a net that is
// gone) do not stop the report: they are listed under "problems" and shown in the page.
// `read_problems`: what read_run_files left out.
nlohmann::json run_report_data(const RunFiles& run, const std::vector<std::string>& read_problems);

// Writes `dir`/report.html atomically and returns its path. Throws OrchError when `dir`
// has no readable result.json.
std::filesystem::path write_run_report(const std::filesystem::path& dir);

}  // namespace orch::report
