#pragma once
// The end of a batch: summary.json, junit.xml and summary.txt, built from nothing but the
// files in one or more batch folders (their batch.json and execution traces). A resumed
// batch and a merge of shards therefore count every run exactly once: a run is counted when
// its execution trace exists, and a run id found twice is refused.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "batch/execution_trace.hpp"
#include "batch/manifest.hpp"

namespace orch::batch {

struct BatchReport {
  std::vector<std::filesystem::path> batch_dirs;
  std::vector<std::string> shards;  // "K/N" per folder that is a shard
  std::size_t total_runs = 0;       // all runs of the batch, over all shards
  std::vector<PlannedEntry> planned;  // runs the folders were to run
  std::map<std::string, ExecutionSummary> done;  // by run id
  std::map<std::string, std::filesystem::path> done_in;  // run id -> its batch folder
  std::optional<double> wall_time_s;

  struct Totals {
    std::size_t success = 0, failure = 0, error = 0, missing = 0;
  };
  // Over the whole batch: runs of shards not collected here count as missing.
  [[nodiscard]] Totals totals() const;
  // Over the runs planned in the collected folders only (what one shard's exit status is about).
  [[nodiscard]] Totals planned_totals() const;
};

// Reads batch.json and executions/ of each folder. Throws OrchError/ScenarioError when a
// folder is no batch, when folders belong to different batches, or when a run appears twice.
BatchReport collect_report(const std::vector<std::filesystem::path>& batch_dirs);

// Writes summary.json, junit.xml and summary.txt (each atomically) into `out_dir`, with
// paths relative to it. Returns the table of summary.txt.
std::string write_reports(const BatchReport& report, const std::filesystem::path& out_dir);

std::string summary_json(const BatchReport& report, const std::filesystem::path& out_dir);
std::string junit_xml(const BatchReport& report);
std::string summary_table(const BatchReport& report);

// 0 every run succeeded, 1 some failed (none errored, none missing), 2 any error or
// missing run: the same meaning as `orchestrator run`'s exit status.
int batch_exit_code(const BatchReport::Totals& t);

}  // namespace orch::batch
