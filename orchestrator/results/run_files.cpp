#include "results/run_files.hpp"

#include "core/errors.hpp"
#include "core/files.hpp"
#include "json/json_document.hpp"
#include "run/metrics_recorder.hpp"
#include "run/trace_writer.hpp"
#include "run/traffic_actions_trace.hpp"
#include "run/traffic_trace.hpp"

namespace orch {

namespace fs = std::filesystem;

const std::vector<std::string>& trace_columns() {
  static const std::vector<std::string> columns = csv_columns(TraceWriter::kHeader);
  return columns;
}

const std::vector<std::string>& metrics_columns() {
  static const std::vector<std::string> columns = csv_columns(metrics::MetricsRecorder::header());
  return columns;
}

const std::vector<std::string>& background_columns() {
  static const std::vector<std::string> columns = csv_columns(TrafficTrace::kBackgroundHeader);
  return columns;
}

const std::vector<std::string>& traffic_actions_columns() {
  static const std::vector<std::string> columns =
      csv_columns(std::string(TrafficTrace::kBackgroundHeader) + TrafficActionsTrace::kExtraColumns);
  return columns;
}

namespace {
std::optional<CsvTable> read_optional(const fs::path& file, const std::vector<std::string>& columns,
                                      std::vector<std::string>* problems) {
  if (!fs::exists(file)) return std::nullopt;
  try {
    return CsvTable::read(file, columns);
  } catch (const OrchError& e) {
    if (!problems) throw;
    problems->push_back(e.what());
    return std::nullopt;
  }
}
}  // namespace

RunFiles read_run_files(const fs::path& dir, std::vector<std::string>* problems) {
  RunFiles f;
  f.dir = dir;
  const fs::path result = dir / "result.json";
  if (!fs::exists(result)) throw OrchError(result.string() + ": no such file (not a run folder?)");
  const JsonDocument doc = JsonDocument::load(result.string());
  if (!doc.root().is_object()) throw ScenarioError(doc.where(""), "expected an object (a run's result.json)");
  f.result = doc.root();
  f.trace = read_optional(dir / "trace.csv", trace_columns(), problems);
  f.metrics = read_optional(dir / "metrics.csv", metrics_columns(), problems);
  f.background = read_optional(dir / "background.csv", background_columns(), problems);
  f.traffic_actions = read_optional(dir / TrafficActionsTrace::kFile, traffic_actions_columns(), problems);
  if (fs::exists(dir / "run.log")) f.run_log = read_file(dir / "run.log");
  return f;
}

}  // namespace orch
