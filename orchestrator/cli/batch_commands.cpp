// `orchestrator sample`, `orchestrator batch` and `orchestrator batch merge`: nightly
// batches of logical scenarios (docs/batches.md, orchestrator/batch/).
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <boost/process.hpp>
#include <cstdlib>
#include <memory>
#include <iostream>
#include <regex>

#include "batch/batch_plan.hpp"
#include "batch/batch_report.hpp"
#include "video/trace_video.hpp"
#include "batch/batch_runner.hpp"
#include "batch/sampling.hpp"
#include "batch/search_runner.hpp"
#include "batch/variation_batch.hpp"
#include "report/search_page.hpp"
#include "reference_driver/ego_model.hpp"
#include "cli/commands.hpp"
#include "cli/subcommand.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/process.hpp"
#include "json/json_text.hpp"

namespace orch::cli {

namespace {

namespace fs = std::filesystem;

struct SampleOptions {
  std::string logical;
  batch::SampleRequest request;  // the CLI options bind straight into it
};

struct BatchCliOptions {
  std::vector<std::string> inputs;
  std::string out = "batch_out";
  std::string resume;
  std::optional<int> jobs;
  std::optional<double> timeout;
  std::optional<int> retries;
  std::string shard;
  std::string wrapper;
  bool video = false;  // --video: video.mp4 of every failing run
  bool ssm = false;    // --ssm: passed to every run
  bool fork = false;     // --fork: one seed per logical scenario, its sets share their prefix
  bool no_fork = false;  // --no-fork: every run from t = 0 in a process of its own
  std::optional<std::string> fork_at;  // --fork-at SECONDS|EVENT: --fork with a checkpoint there
  std::string ego_model;       // --ego-model: passed to every run
  bool reference_run = false;  // --reference-run: passed to every run
  std::string controllers;     // --controllers on|off: passed to every run
  CommonOptions common;
};

struct SearchCliOptions {
  batch::SearchOptions search;
  std::string out = "search_out";
  std::string resume;
  std::optional<int> jobs;
  std::optional<double> timeout;
  bool minimize = false;
  CommonOptions common;
};

struct MergeOptions {
  std::vector<std::string> dirs;
  std::string out;
};

// Bad input files are reported like `validate` does: every problem, file:line: pointer.
int report_input_error(const ScenarioError& e) {
  std::cerr << e.diagnostics().format();
  return 1;
}

int sample_command(const SampleOptions& o) {
  try {
    // An OpenSCENARIO parameter variation is a logical scenario too (batch/variation_batch.hpp).
    const batch::SampleOutcome outcome =
        batch::is_variation_input(o.logical)
            ? batch::sample_variation_sets(*batch::load_variation_logical(o.logical), o.request)
            : batch::sample_parameter_sets(batch::load_logical_scenario(o.logical), o.request);
    write_file_atomically(outcome.file.file, batch::to_json_text(outcome.file));
    std::cout << fmt::format("{}: {} new parameter set(s), {} in all\n", outcome.file.file.string(),
                             outcome.new_set_ids.size(), outcome.file.sets.size());
    for (const auto& id : outcome.new_set_ids) {
      const batch::ParameterSet* set = outcome.file.find(id);
      std::cout << fmt::format("  {} seed {}: {}\n", id, set->seed.value_or(0), json_text(set->sampled_values));
    }
    return 0;
  } catch (const ScenarioError& e) {
    return report_input_error(e);
  }
}

// Flags `orchestrator run` offers, read from its --help: the batch passes sumo_config
// settings (traffic, backend) only through flags that exist, whoever adds them.
std::set<std::string> run_flags_of(const fs::path& exe) {
  const std::string text = run_process(exe.string(), {"run", "--help"}).output;
  std::set<std::string> flags;
  const std::regex flag("--[a-z][a-z0-9-]*");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), flag); it != std::sregex_iterator(); ++it)
    flags.insert(it->str());
  return flags;
}

std::string resolve_program(const std::string& program) {
  if (program.empty() || program.find('/') != std::string::npos) return program.empty() ? "" : fs::absolute(program).string();
  const auto found = boost::process::search_path(program);
  if (found.empty()) throw OrchError(fmt::format("--wrapper: cannot find \"{}\" in PATH", program));
  return found.string();
}

int batch_command(const BatchCliOptions& o, const CLI::App& app) {
  batch::BatchOptions b;
  b.inputs = o.inputs;
  b.resume = !o.resume.empty();
  if (b.resume && app.count("--out") && fs::absolute(o.out) != fs::absolute(o.resume))
    throw OrchError("--resume DIR continues the batch in DIR: give no other --out");
  b.out = b.resume ? o.resume : o.out;
  if (!b.resume && b.inputs.empty()) throw OrchError("batch: give logical scenarios or parameter files, or --resume DIR");
  b.jobs = o.jobs;
  b.timeout_s = o.timeout;
  b.retries = o.retries;
  if (!o.shard.empty()) b.shard = batch::parse_shard(o.shard);
  b.map_dirs = o.common.map_dirs;
  for (auto& d : b.map_dirs) d = fs::absolute(d).string();  // the children run elsewhere
  b.catalog = o.common.catalog.empty() ? "" : fs::absolute(o.common.catalog).string();
  b.wrapper = resolve_program(o.wrapper);
  b.ssm = o.ssm;
  b.fork = o.fork || o.fork_at.has_value();
  b.no_fork = o.no_fork;
  if (o.fork_at) b.fork_at = parse_fork_checkpoint(*o.fork_at);
  if (b.fork && o.no_fork) throw OrchError(fmt::format("{} and --no-fork contradict each other: give one", o.fork_at ? "--fork-at" : "--fork"));
  if (o.video) {
    if (const auto missing = video::missing_video_tools(); !missing.empty()) throw OrchError("batch " + missing);
  }
  b.orchestrator = fs::read_symlink("/proc/self/exe");
  b.run_flags = run_flags_of(b.orchestrator);
  if (!o.ego_model.empty()) b.run_args = {"--ego-model", o.ego_model};
  if (o.reference_run) b.run_args.emplace_back("--reference-run");
  if (!o.controllers.empty()) {
    if (o.controllers == "off" && (!o.ego_model.empty() || o.reference_run))
      throw OrchError(fmt::format("--controllers off: every entity follows the storyboard; {} asks for a driver of "
                                  "the ego: give one or the other", o.reference_run ? "--reference-run" : "--ego-model"));
    b.run_args.insert(b.run_args.end(), {"--controllers", o.controllers});
  }
  b.out_stream = &std::cout;
  b.terminal = ::isatty(STDOUT_FILENO) == 1;
  try {
    const int code = batch::run_batch(b);
    if (o.video) announce_failure_videos(b.out);
    announce_batch_report({b.out}, b.out);
    return code;
  } catch (const ScenarioError& e) {
    std::cerr << e.diagnostics().format();
    return 2;
  }
}

void announce_search_report(const fs::path& dir) {
  try {
    std::cout << "search report: file://" << fs::absolute(report::write_search_report(dir)).string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "warning: no search.html for " << dir.string() << ": " << e.what() << "\n";
  }
}

int search_command(const SearchCliOptions& o, const CLI::App& app) {
  batch::SearchOptions s = o.search;
  batch::BatchOptions& b = s.batch;
  b.resume = !o.resume.empty();
  if (b.resume && app.count("--out") && fs::absolute(o.out) != fs::absolute(o.resume))
    throw OrchError("--resume DIR continues the search in DIR: give no other --out");
  b.out = b.resume ? o.resume : o.out;
  if (!b.resume && s.input.empty()) throw OrchError("search: give a logical scenario or a variation file, or --resume DIR");
  if (o.minimize && !s.boundary.empty()) throw OrchError("search: --minimize and --boundary exclude each other");
  if (!b.resume && !o.minimize && s.boundary.empty())
    throw OrchError("search: give --minimize (falsification: minimise --objective) or --boundary CRITERION");
  if (!b.resume && o.minimize && s.objective.empty()) throw OrchError("search: --minimize needs --objective METRIC");
  b.jobs = o.jobs;
  b.timeout_s = o.timeout;
  b.map_dirs = o.common.map_dirs;
  for (auto& d : b.map_dirs) d = fs::absolute(d).string();
  b.catalog = o.common.catalog.empty() ? "" : fs::absolute(o.common.catalog).string();
  b.wrapper = resolve_program(b.wrapper);
  b.orchestrator = fs::read_symlink("/proc/self/exe");
  b.run_flags = run_flags_of(b.orchestrator);
  b.out_stream = &std::cout;
  b.terminal = ::isatty(STDOUT_FILENO) == 1;
  try {
    const int code = batch::run_search(s);
    announce_batch_report({b.out}, b.out);
    announce_search_report(b.out);
    return code;
  } catch (const ScenarioError& e) {
    std::cerr << e.diagnostics().format();
    return 2;
  }
}

int merge_command(const MergeOptions& o) {
  std::vector<fs::path> dirs(o.dirs.begin(), o.dirs.end());
  const batch::BatchReport report = batch::collect_report(dirs);
  std::cout << batch::write_reports(report, o.out);
  std::cout << fmt::format("\nmerged {} folder(s) into {} (summary.json, junit.xml, summary.txt)\n", dirs.size(), o.out);
  announce_batch_report(dirs, o.out);
  return batch::batch_exit_code(report.totals());
}

Handler setup_sample(CLI::App& cmd) {
  auto o = std::make_shared<SampleOptions>();
  // Input files are not checked here: a missing one is reported as bad input (file: error).
  cmd.add_option("logical", o->logical, "Logical scenario (logical_{uuid}.json)")->required();
  cmd.add_option("--count", o->request.count, "Parameter sets to add")->required()->check(CLI::Range(1, 1000000));
  cmd.add_option("--seed", o->request.first_seed, "Seed of the first new set; the next take seed+1, ... (skipping used ones)")
      ->capture_default_str()
      ->check(CLI::Range(0LL, 2147483647LL));
  cmd.add_option("--step", o->request.step, "sumo_config.step of the new sets, s")->check(CLI::Range(0.001, 1.0));
  cmd.add_option("--max-time", o->request.max_time, "sumo_config.max_time of the new sets, s")
      ->check(CLI::Range(1e-9, 1e7));
  cmd.add_option("--traffic", o->request.traffic, "sumo_config.traffic of the new sets (passed to run --traffic)");
  cmd.add_option("--backend", o->request.backend, "sumo_config.backend of the new sets (passed to run --backend)");
  return [o] { return sample_command(*o); };
}

Handler setup_batch(CLI::App& cmd) {
  auto o = std::make_shared<BatchCliOptions>();
  cmd.require_subcommand(0, 1);
  cmd.add_option("inputs", o->inputs, "Logical scenarios and/or parameter files");
  cmd.add_option("--out", o->out, "Output folder of the batch")->capture_default_str();
  cmd.add_option("--resume", o->resume, "Continue the batch in this folder: run exactly the runs not done")
      ->check(CLI::ExistingDirectory);
  cmd.add_option("--jobs,-j", o->jobs, "Runs at a time (default: the number of cores)")->check(CLI::Range(1, 1024));
  cmd.add_option("--timeout", o->timeout, "Wall-clock limit per run, s; its process tree is then killed (default 1800)")
      ->check(CLI::Range(1e-3, 1e7));
  cmd.add_option("--retries", o->retries, "Extra attempts for runs ending in error (default 1); failures are never retried")
      ->check(CLI::Range(0, 100));
  cmd.add_option("--shard", o->shard, "Run only shard K of N (K/N, 1-based): a deterministic 1/N of the runs");
  cmd.add_option("--wrapper", o->wrapper, "Start each run through this program (e.g. nice)");
  cmd.add_flag("--video", o->video, "Write video.mp4 of every failing run (sumo-gui, ffmpeg)");
  cmd.add_flag("--ssm", o->ssm, "Pass --ssm to every run: SUMO's SSM device on the ego (ssm.xml)");
  cmd.add_flag("--fork", o->fork,
               "Run the sets of each logical scenario with one seed (its first set's) so that they run their common "
               "prefix once (docs/forking.md)");
  cmd.add_flag("--no-fork", o->no_fork, "Run every set from t = 0 in a process of its own, even sets that share a seed");
  cmd.add_option("--fork-at", o->fork_at,
                 "--fork, and every set continues in a process of its own from this SUMO time (s) on, or from the "
                 "step an event happens (scene:N entered, a storyboard element of that name started); sets whose "
                 "commands part earlier still part there, with a warning in fork.json (docs/forking.md)");
  cmd.add_option("--ego-model", o->ego_model, "What drives the ego in every run: sumo, r157 or cruise (run --ego-model)")
      ->check(CLI::IsMember(ego_model_names()));
  cmd.add_flag("--reference-run", o->reference_run,
               "Give every run a reference run with the R157 reference driver (run --reference-run): the "
               "`preventable` column");
  cmd.add_option("--controllers", o->controllers,
                 "on or off, passed to every run (run --controllers): off, no controller runs and every entity "
                 "follows the storyboard")
      ->check(CLI::IsMember({"on", "off"}));
  cmd.add_option("--maps", o->common.map_dirs, "Folder holding map folders (repeatable), passed to every run")
      ->allow_extra_args(false);
  cmd.add_option("--catalog", o->common.catalog, "Model catalog JSON, passed to every run");
  return [o, &cmd] { return batch_command(*o, cmd); };
}

Handler setup_search(CLI::App& cmd) {
  auto o = std::make_shared<SearchCliOptions>();
  batch::SearchOptions& s = o->search;
  cmd.add_option("input", s.input, "Logical scenario (logical_{uuid}.json) or OpenSCENARIO variation (X_variation.xosc)");
  cmd.add_option("--objective", s.objective,
                 "What to minimise / colour runs by: METRIC of the ego (min_ttc, min_gap, ...), ACTOR.METRIC, sim_time "
                 "or criterion:NAME");
  cmd.add_flag("--minimize", o->minimize, "Falsification: find the runs with the smallest --objective");
  cmd.add_option("--boundary", s.boundary,
                 "Find where CRITERION flips between pass and fail: verdict, collision or a criterion's name");
  cmd.add_option("--budget", s.budget, "Runs in all")->check(CLI::Range(1, 100000));
  cmd.add_option("--jobs,-j", o->jobs, "Runs at a time, and points proposed per iteration (default: the number of cores)")
      ->check(CLI::Range(1, 1024));
  cmd.add_option("--seed", s.seed, "Seed of the search (and SUMO's seed of every run; default 1)")
      ->check(CLI::Range(0LL, 2147483647LL));
  cmd.add_option("--method", s.method, "bo (Gaussian-process search, default), random or grid (the baselines)");
  cmd.add_option("--set", s.set_words, "Fix a parameter (KEY=VALUE) or narrow its range (KEY=LOW..HIGH); repeatable")
      ->allow_extra_args(false);
  cmd.add_option("--max-time", s.max_time, "max_time of every run, s (default: the logical scenario's)")
      ->check(CLI::Range(1e-9, 1e7));
  cmd.add_option("--resolution", s.resolution,
                 "Boundary: refine cells down to this fraction of each range (default 1/64 = 0.015625)")
      ->check(CLI::Range(1e-4, 1.0));
  cmd.add_option("--out", o->out, "Output folder of the search")->capture_default_str();
  cmd.add_option("--resume", o->resume, "Continue the search in this folder (a larger --budget extends it)")
      ->check(CLI::ExistingDirectory);
  cmd.add_option("--timeout", o->timeout, "Wall-clock limit per run, s (default 1800)")->check(CLI::Range(1e-3, 1e7));
  cmd.add_option("--wrapper", s.batch.wrapper, "Start each run through this program (e.g. nice)");
  cmd.add_flag("--no-fork", s.batch.no_fork,
               "Run every point from t = 0 in a process of its own (by default the points of an iteration share "
               "their common prefix: docs/forking.md)");
  cmd.add_option("--maps", o->common.map_dirs, "Folder holding map folders (repeatable), passed to every run")
      ->allow_extra_args(false);
  cmd.add_option("--catalog", o->common.catalog, "Model catalog JSON, passed to every run");
  return [o, &cmd] { return search_command(*o, cmd); };
}

Handler setup_merge(CLI::App& cmd) {
  auto o = std::make_shared<MergeOptions>();
  cmd.add_option("dirs", o->dirs, "Batch folders (e.g. one per shard)")->required()->check(CLI::ExistingDirectory);
  cmd.add_option("--out", o->out, "Folder for the merged summary.json, junit.xml, summary.txt")->required();
  return [o] { return merge_command(*o); };
}

}  // namespace

std::vector<Subcommand> batch_subcommands() {
  return {{{"sample"}, "Add seeded parameter sets to a logical scenario's parameter file", setup_sample},
          {{"batch"}, "Run every parameter set of logical scenarios, in parallel child processes", setup_batch},
          {{"batch", "merge"}, "Combine batch (shard) folders into one summary and JUnit file", setup_merge},
          {{"search"}, "Search a logical scenario's parameter space for critical runs or a pass/fail boundary",
           setup_search}};
}

}  // namespace orch::cli
