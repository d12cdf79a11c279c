#include "batch/attempt.hpp"

#include <fmt/format.h>

#include <cstring>

#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/object_reader.hpp"

namespace orch::batch {

namespace {

int exit_code_of(const std::string& verdict) {
  if (verdict == "success") return 0;
  if (verdict == "failure") return 1;
  return 2;
}

// Reads the verdict of result.json into `a`; returns "" or why it could not.
std::string read_result(const std::filesystem::path& file, Attempt& a) {
  if (!std::filesystem::exists(file)) return "no result.json";
  try {
    const JsonDocument doc = JsonDocument::load(file.string());
    Diagnostics diags;
    ObjectReader r(doc, doc.root(), "", diags, "run result");
    const auto verdict = r.choice("verdict", {"success", "failure", "error"}, Need::Required);
    const auto reason = r.string("reason", Need::Optional);
    a.sim_time = r.number("sim_time", Need::Optional);
    a.run_wall_time_s = r.number("wall_time_s", Need::Optional);
    // The evaluation's figures travel on to summary.json and the batch's metrics.csv as they are.
    if (doc.root().contains("metrics") && doc.root()["metrics"].is_object()) a.metrics = doc.root()["metrics"];
    if (doc.root().contains("criteria") && doc.root()["criteria"].is_array()) a.criteria = doc.root()["criteria"];
    if (doc.root().contains("preventable") && doc.root()["preventable"].is_string())
      a.preventable = doc.root()["preventable"].get<std::string>();
    // The rest of result.json is the run's business; only these keys matter here.
    if (diags.has_errors() || !verdict) return "result.json unreadable: " + diags.format();
    a.verdict = *verdict;
    a.reason = reason.value_or("");
    return {};
  } catch (const OrchError& e) {
    return std::string("result.json unreadable: ") + e.what();
  }
}

}  // namespace

Attempt judge_attempt(const ChildExit& exit, const std::string& start_error, const std::filesystem::path& result_file,
                      std::optional<double> timeout_s) {
  Attempt a;
  a.exit_code = exit.exit_code;
  a.signal = exit.signal;
  a.timed_out = exit.timed_out;
  a.wall_time_s = exit.wall_time_s;
  if (!start_error.empty()) {
    a.reason = "could not start the run: " + start_error;
    return a;
  }
  if (exit.timed_out) {
    a.reason = fmt::format("timed out after {:g} s (wall clock); its process tree was killed", timeout_s.value_or(0));
    return a;
  }
  if (exit.signal) {
    a.reason = fmt::format("crashed: killed by signal {} ({})", *exit.signal, ::strsignal(*exit.signal));
    return a;
  }
  const int code = exit.exit_code.value_or(-1);
  Attempt judged = a;
  const std::string problem = read_result(result_file, judged);
  if (!problem.empty()) {
    a.reason = code == 127 ? "the run program could not be executed (exit 127)"
                           : fmt::format("exit code {} and {} (see child.log)", code, problem);
    return a;
  }
  if (exit_code_of(judged.verdict) != code) {
    a.reason = fmt::format("exit code {} contradicts result.json's verdict \"{}\" ({})", code, judged.verdict,
                           judged.reason);
    a.sim_time = judged.sim_time;
    return a;
  }
  return judged;
}

std::optional<int> verdict_exit_code(const std::filesystem::path& result_file) {
  Attempt a;
  if (!read_result(result_file, a).empty()) return std::nullopt;
  return exit_code_of(a.verdict);
}

}  // namespace orch::batch
