#include "run/result_jsonl.hpp"

#include <fmt/format.h>

#include <chrono>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "run/run_result.hpp"

namespace orch {

namespace {

double system_stamp() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

nlohmann::ordered_json stamp(double simulation) {
  return {{"System", system_stamp()}, {"Simulation", simulation}};
}

const char* success_fail(bool ok) { return ok ? "Success" : "Fail"; }

}  // namespace

ResultJsonl::ResultJsonl(const std::filesystem::path& path, const nlohmann::json& conditions, int every)
    : file_(path, nlohmann::ordered_json{{"Condition", conditions}}.dump()), every_(std::max(1, every)) {}

void ResultJsonl::frame(const criteria::FrameReport& report) {
  last_time_ = report.time;
  if (steps_++ % every_ != 0) return;
  nlohmann::ordered_json frames = nlohmann::ordered_json::object();
  std::string failing;
  for (const auto& [state, f] : report.frames) {
    const bool total = state->holds();
    if (!total) failing += (failing.empty() ? "" : ", ") + state->spec().name;
    nlohmann::ordered_json info{{"Measured", f.measured}};
    if (f.value) info["Value"] = *f.value;
    if (!f.partner.empty()) info["Partner"] = f.partner;
    frames[state->spec().name] = {{"Result", {{"Total", success_fail(total)}, {"Frame", success_fail(f.ok)}}},
                                  {"Info", info}};
  }
  const std::string summary = failing.empty() ? fmt::format("Passed: {} criteria hold", report.frames.size())
                                              : "Failed: " + failing;
  file_.line(nlohmann::ordered_json{{"Result", {{"Success", failing.empty()}, {"Summary", summary}}},
                                    {"Stamp", stamp(report.time)},
                                    {"Frame", frames}}
                 .dump());
}

namespace {
nlohmann::ordered_json final_line(const RunResult& result) {
  const bool ok = result.verdict == Verdict::Success;
  const std::string summary = std::string(ok ? "Passed: " : "Failed: ") +
                              (result.verdict == Verdict::Error ? "error: " : "") + result.reason;
  return {{"Result", {{"Success", ok}, {"Summary", summary}}},
          {"Stamp", stamp(result.sim_time)},
          {"Frame", nlohmann::ordered_json::object()}};
}
}  // namespace

void ResultJsonl::finish(RunResult& result) noexcept {
  try {
    file_.line(final_line(result).dump());
  } catch (const std::exception&) {
    // fmt failing to write: the file stays as it is, result.json still says everything.
  }
  file_.flush();
}

void write_unstarted_jsonl(const std::filesystem::path& path, const nlohmann::json& conditions, const RunResult& result) {
  const nlohmann::ordered_json condition{{"Condition", conditions}};
  write_file_atomically(path, condition.dump() + "\n" + final_line(result).dump() + "\n");
}

void write_format_error_jsonl(const std::filesystem::path& path, const Diagnostics& diagnostics) {
  std::string first;
  for (const auto& d : diagnostics.items())
    if (d.severity == Severity::Error) {
      first = d.format();
      break;
    }
  nlohmann::ordered_json condition{{"Condition", nlohmann::ordered_json::object()}};
  nlohmann::ordered_json last{{"Result", {{"Success", false}, {"Summary", "ScenarioFormatError: " + first}}},
                              {"Stamp", {{"System", system_stamp()}, {"Simulation", 0.0}}},
                              {"Frame", nlohmann::ordered_json::object()}};
  write_file_atomically(path, condition.dump() + "\n" + last.dump() + "\n");
}

}  // namespace orch
