// report.html of runs and batches (README "Looking at results"), and `orchestrator report`.
#include <fmt/format.h>

#include <chrono>

#include <iostream>
#include <nlohmann/json.hpp>

#include "batch/batch_report.hpp"
#include "cli/commands.hpp"
#include "core/files.hpp"
#include "report/batch_page.hpp"
#include "report/run_report.hpp"
#include "video/trace_video.hpp"

namespace orch::cli {

namespace fs = std::filesystem;

namespace {
std::string file_url(const fs::path& p) { return "file://" + fs::absolute(p).lexically_normal().string(); }

// "report: file://... (0.031 s)": what writing it cost, the figure docs/reports.md quotes.
template <class Write>
void announce(Write&& write, const char* what = "report") {
  const auto start = std::chrono::steady_clock::now();
  const fs::path written = write();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << fmt::format("{}: {} ({:.3f} s)\n", what, file_url(written), s);
}

// The batch's wall time as summary.json recorded it (a report written later keeps it).
std::optional<double> recorded_wall_time(const fs::path& out_dir) {
  try {
    const auto j = nlohmann::json::parse(read_file(out_dir / "summary.json"));
    if (j.contains("wall_time_s") && j["wall_time_s"].is_number()) return j["wall_time_s"].get<double>();
  } catch (const std::exception&) {
  }
  return std::nullopt;
}
}  // namespace

bool announce_run_report(const fs::path& run_dir) {
  try {
    announce([&] { return report::write_run_report(run_dir); });
    return true;
  } catch (const std::exception& e) {
    std::cerr << "warning: no report.html for " << run_dir.string() << ": " << e.what() << "\n";
    return false;
  }
}

bool announce_video(const fs::path& run_dir) {
  try {
    announce([&] { return video::write_video(run_dir); }, "video");
    return true;
  } catch (const std::exception& e) {
    std::cerr << "warning: no video.mp4 for " << run_dir.string() << ": " << e.what() << "\n";
    return false;
  }
}

void announce_failure_videos(const fs::path& batch_dir) {
  const batch::BatchReport collected = batch::collect_report({batch_dir});
  for (const auto& [id, run] : collected.done)
    if (run.verdict == "failure") announce_video(collected.done_in.at(id) / run.run_dir);
}

bool announce_batch_report(const std::vector<fs::path>& batch_dirs, const fs::path& out_dir) {
  try {
    announce([&] {
      batch::BatchReport collected = batch::collect_report(batch_dirs);
      collected.wall_time_s = recorded_wall_time(out_dir);
      return report::write_batch_report(collected, out_dir);
    });
    return true;
  } catch (const std::exception& e) {
    std::cerr << "warning: no report.html for " << out_dir.string() << ": " << e.what() << "\n";
    return false;
  }
}

int report_command(const ReportOptions& o) {
  bool all = true;
  for (const auto& d : o.dirs) {
    const fs::path dir = d;
    if (fs::exists(dir / "batch.json")) all = announce_batch_report({dir}, dir) && all;
    else if (fs::exists(dir / "result.json")) all = announce_run_report(dir) && all;
    else {
      std::cerr << fmt::format("{}: neither a run folder (result.json) nor a batch folder (batch.json)\n", d);
      all = false;
    }
  }
  return all ? 0 : 2;
}

}  // namespace orch::cli
