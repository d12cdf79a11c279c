#pragma once
// The one-file HTML page both reports are: styles, Chart.js (Debian's libjs-chart.js,
// compiled in), the page's own script and its data, all inline, so the file opens from
// disk with no server and no network.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace orch::report {

// `page_script` is the report's own script (run or batch); `data` becomes
// <script type="application/json" id="report-data">, escaped so that no text in it can end
// the element.
std::string html_page(std::string_view title, std::string_view page_script, const nlohmann::json& data);

// The embedded scripts of the two kinds of report.
std::string_view run_report_script();
std::string_view batch_report_script();

}  // namespace orch::report
