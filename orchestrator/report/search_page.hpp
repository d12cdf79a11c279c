#pragma once
// search.html of an `orchestrator search` folder (batch/search_runner.hpp): the parameter
// space with every run as a dot coloured by the objective (two searched parameters at a
// time; one parameter against the objective), the boundary estimate shaded behind them,
// the most critical runs and every iteration, each run linked to its run report. Built from
// search.json alone; static SVG, so the page opens from disk with no script.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace orch::report {

std::string search_page_html(const nlohmann::json& search);
// Writes DIR/search.html from DIR/search.json; returns its path. Throws OrchError when the
// folder holds no search.json.
std::filesystem::path write_search_report(const std::filesystem::path& dir);

}  // namespace orch::report
