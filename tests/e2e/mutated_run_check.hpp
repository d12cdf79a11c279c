#pragma once
// The property every mutated input must keep (tests/e2e/test_mutated_*_cli.cpp): `run`
// exits 0, 1 or 2, writes a parseable result.json whose verdict matches the exit status and
// whose reason is no internal error, prints valid UTF-8 and leaves no process behind. Each
// mutant is also printed on one line (seed, index, file, mutation, exit, seconds): the soak
// (scripts/soak.sh) counts and times them from these lines.
#include <gtest/gtest.h>
#include <sys/prctl.h>
#include <sys/wait.h>

#include <chrono>
#include <iostream>

#include "core/utf8.hpp"
#include "support/cli_runner.hpp"
#include "support/mutation.hpp"
#include "support/process_tree.hpp"

namespace orch::test {

// Processes that are still our children: the orchestrator's orphans come to us (subreaper).
inline std::vector<pid_t> live_children() {
  while (::waitpid(-1, nullptr, WNOHANG) > 0) {
  }
  std::vector<pid_t> pids;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = std::stoi(name);
    const auto info = proc_info(pid);
    if (info && info->ppid == ::getpid() && process_alive(pid)) pids.push_back(pid);
  }
  return pids;
}

// While alive, the test process adopts the orchestrator's orphans.
class SubreaperScope {
 public:
  SubreaperScope() { ok_ = ::prctl(PR_SET_CHILD_SUBREAPER, 1) == 0; }
  ~SubreaperScope() { ::prctl(PR_SET_CHILD_SUBREAPER, 0); }
  SubreaperScope(const SubreaperScope&) = delete;
  SubreaperScope& operator=(const SubreaperScope&) = delete;
  [[nodiscard]] bool ok() const { return ok_; }

 private:
  bool ok_ = false;
};

// Runs `file` (a mutant of `source`) and checks the property; `label` names the mutant.
inline void run_mutant_and_check(const std::string& kind, std::uint64_t seed, int index, const std::filesystem::path& source,
                                 const Mutation& m, const std::filesystem::path& file,
                                 const std::vector<std::string>& extra) {
  SCOPED_TRACE(source.filename().string() + ": " + m.what + " (ORCH_PROPERTY_SEED=" + std::to_string(seed) +
               ", mutant " + std::to_string(index) + ")");
  TempDir out;
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_scenario(file.string(), out, extra);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "mutant " << kind << " seed=" << seed << " index=" << index << " file=" << source.filename().string()
            << " exit=" << r.exit_code << " seconds=" << seconds << " what=" << m.what << "\n";
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2) << r.exit_code << "\n" << r.output;
  EXPECT_TRUE(orch::is_valid_utf8(r.output));
  ASSERT_TRUE(std::filesystem::exists(out / "result.json")) << r.output;
  const auto result = read_json(out / "result.json");
  const std::string verdict = result["verdict"].get<std::string>();
  EXPECT_EQ(r.exit_code, verdict == "success" ? 0 : verdict == "failure" ? 1 : 2) << verdict;
  EXPECT_EQ(result["reason"].get<std::string>().find("internal error"), std::string::npos) << result["reason"];
  EXPECT_TRUE(live_children().empty()) << "a process outlived the run";
}

// One mutant written to disk: what was done, the file to run, and the original it came from.
struct WrittenMutant {
  Mutation mutation;
  std::filesystem::path file;
  std::filesystem::path source;
};

// Every mutant of the seeds in `p`: each draws an original from `files` and `make(original,
// rng, stem)` writes its mutant (files named `stem` + extension); then the property is checked.
template <class Make>
void check_mutants(const std::string& kind, const std::vector<std::filesystem::path>& files, const PropertySeeds& p,
                   const std::vector<std::string>& run_options, Make make) {
  ASSERT_FALSE(files.empty());
  SubreaperScope reaper;
  ASSERT_TRUE(reaper.ok());
  TempDir dir;
  for (const std::uint64_t seed : p.seeds) {
    std::cout << kind << " mutants: ORCH_PROPERTY_SEED=" << seed << ", " << p.runs << " runs\n";
    std::mt19937_64 rng(seed);
    for (int i = 0; i < p.runs; ++i) {
      const std::filesystem::path& original = files[rng() % files.size()];
      const WrittenMutant w = make(original, rng, (dir / ("mutated_" + std::to_string(seed) + "_" + std::to_string(i))).string());
      run_mutant_and_check(kind, seed, i, w.source, w.mutation, w.file, run_options);
    }
  }
}

}  // namespace orch::test
