#include "report/html_page.hpp"

#include <fmt/format.h>

#include "core/xml_text.hpp"

namespace orch::embedded {
std::string_view chartjs_js();
std::string_view report_css();
std::string_view report_common_js();
std::string_view run_report_js();
std::string_view batch_report_js();
}  // namespace orch::embedded

namespace orch::report {

namespace {

// JSON inside <script>: '<' only occurs in strings, where \u003c means the same, so no
// "</script>" or "<!--" in a scenario's text can end the element early.
std::string script_safe_json(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

}  // namespace

std::string_view run_report_script() { return embedded::run_report_js(); }
std::string_view batch_report_script() { return embedded::batch_report_js(); }

std::string html_page(std::string_view title, std::string_view page_script, const nlohmann::json& data) {
  std::string page;
  page.reserve(embedded::chartjs_js().size() + 200000);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += fmt::format("<title>{}</title>\n<style>\n", xml_escape(title));
  page += embedded::report_css();
  page += "</style>\n</head>\n<body>\n<div id=\"app\"></div>\n";
  page += "<script type=\"application/json\" id=\"report-data\">";
  page += script_safe_json(data);
  page += "</script>\n<script>\n";
  page += embedded::chartjs_js();
  page += "\n</script>\n<script>\n";
  page += embedded::report_common_js();
  page += "\n</script>\n<script>\n";
  page += page_script;
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace orch::report
