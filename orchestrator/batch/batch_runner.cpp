#include "batch/batch_runner.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <map>
#include <thread>

#include "batch/attempt.hpp"
#include "batch/batch_report.hpp"
#include "batch/execution_trace.hpp"
#include "batch/fork_event_check.hpp"
#include "batch/fork_groups.hpp"
#include "batch/identifiers.hpp"
#include "batch/manifest.hpp"
#include "batch/progress.hpp"
#include "batch/run_queue.hpp"
#include "batch/sampling.hpp"
#include "batch/template_file.hpp"
#include "core/errors.hpp"
#include "core/files.hpp"

namespace orch::batch {

namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

constexpr double kDefaultTimeout = 1800;
constexpr int kDefaultRetries = 1;

// One batch per folder at a time: a second `--resume` of a running batch would run the
// same runs twice. flock is released by the kernel however the holder dies.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir) {
    const fs::path file = dir / ".lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0 || ::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw OrchError(fmt::format("another batch is running in {} (it holds {})", dir.string(), file.string()));
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

// What a resumed batch takes from batch.json unless given again.
void apply_manifest_defaults(BatchOptions& o, const Manifest& m) {
  const auto& opt = m.options;
  if (!o.jobs && opt.contains("jobs") && opt["jobs"].is_number_integer()) o.jobs = opt["jobs"].get<int>();
  if (!o.timeout_s && opt.contains("timeout_s") && opt["timeout_s"].is_number()) o.timeout_s = opt["timeout_s"].get<double>();
  if (!o.retries && opt.contains("retries") && opt["retries"].is_number_integer()) o.retries = opt["retries"].get<int>();
  if (o.map_dirs.empty() && opt.contains("maps") && opt["maps"].is_array())
    for (const auto& d : opt["maps"]) o.map_dirs.push_back(d.get<std::string>());
  if (o.catalog.empty() && opt.contains("catalog") && opt["catalog"].is_string()) o.catalog = opt["catalog"].get<std::string>();
  if (o.wrapper.empty() && opt.contains("wrapper") && opt["wrapper"].is_string()) o.wrapper = opt["wrapper"].get<std::string>();
  if (!o.ssm && opt.contains("ssm") && opt["ssm"].is_boolean()) o.ssm = opt["ssm"].get<bool>();
  if (!o.fork && opt.contains("fork") && opt["fork"].is_boolean()) o.fork = opt["fork"].get<bool>();
  if (!o.no_fork && opt.contains("no_fork") && opt["no_fork"].is_boolean()) o.no_fork = opt["no_fork"].get<bool>();
  if (!o.fork_at && opt.contains("fork_at") && opt["fork_at"].is_number()) o.fork_at = ForkCheckpoint{opt["fork_at"].get<double>(), ""};
  if (!o.fork_at && opt.contains("fork_at") && opt["fork_at"].is_string())
    o.fork_at = parse_fork_checkpoint(opt["fork_at"].get<std::string>());
  // --ego-model and --reference-run: every run of the batch drives its ego the same way.
  if (o.run_args.empty() && opt.contains("run_args") && opt["run_args"].is_array())
    for (const auto& a : opt["run_args"])
      if (a.is_string()) o.run_args.push_back(a.get<std::string>());
}

ordered_json options_json(const BatchOptions& o) {
  return {{"jobs", *o.jobs}, {"timeout_s", *o.timeout_s}, {"retries", *o.retries}, {"maps", o.map_dirs},
          {"catalog", o.catalog}, {"wrapper", o.wrapper}, {"ssm", o.ssm}, {"run_args", o.run_args},
          {"fork", o.fork}, {"no_fork", o.no_fork},
          {"fork_at", !o.fork_at         ? ordered_json(nullptr)
                      : o.fork_at->time_s ? ordered_json(*o.fork_at->time_s)
                                          : ordered_json(o.fork_at->event)}};
}

void verify_unchanged(const Manifest& m, const BatchPlan& plan) {
  for (const auto& [path, sha] : plan.input_hashes) {
    const auto it = m.input_sha256.find(path);
    if (it == m.input_sha256.end() || it->second != sha)
      throw OrchError(fmt::format("{} changed since the batch started; its results would not belong together: "
                                  "start a new batch (another --out)", path));
  }
  std::vector<std::string> planned, now;
  for (const auto& r : m.runs) planned.push_back(r.id);
  for (const auto& r : plan.runs) now.push_back(r.id);
  if (planned != now)
    throw OrchError(fmt::format("the inputs now give {} runs where the batch planned {}; start a new batch",
                                now.size(), planned.size()));
}

// Runs already done: their execution trace exists and reads. A trace that does not read
// cannot come from the atomic writer; it is set aside and the run done again.
std::vector<bool> find_done(const fs::path& out, const BatchPlan& plan, std::ostream& msg) {
  for (const auto& entry : fs::directory_iterator(out / "executions"))
    if (entry.path().filename().string().find(".tmp") != std::string::npos) fs::remove(entry.path());
  std::vector<bool> done(plan.runs.size(), false);
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const fs::path file = execution_trace_path(out, plan.runs[i].id);
    if (!fs::exists(file)) continue;
    try {
      read_execution_summary(file);
      done[i] = true;
    } catch (const OrchError& e) {
      msg << "batch: " << file.string() << " is unreadable; the run is done again (" << e.what() << ")\n";
      fs::rename(file, file.string() + ".unreadable");
    }
  }
  return done;
}

// Before attempt 1 the run folder starts empty; before a retry, only the logs of the
// earlier attempts (attempt*.log) stay.
void prepare_run_dir(const fs::path& dir, int attempt) {
  if (attempt == 1) {
    fs::remove_all(dir);
  } else if (fs::exists(dir)) {
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().filename().string().rfind("attempt", 0) != 0) fs::remove_all(entry.path());
  }
  fs::create_directories(dir);
}

void keep_attempt_logs(const fs::path& dir, int attempt) {
  for (const char* log : {"child.log", "run.log"}) {
    std::error_code ec;
    fs::rename(dir / log, dir / fmt::format("attempt{}.{}", attempt, log), ec);
  }
}

std::string label_of(const PlannedRun& run) {
  const std::string name = run.name.empty() ? run.logical_uuid : run.name;
  return run.set.seed ? fmt::format("{} seed {}", name, *run.set.seed) : fmt::format("{} {}", name, run.parameter_uuid);
}

}  // namespace

std::vector<std::string> pass_through_flags(const SumoConfig& config, const std::set<std::string>& run_flags) {
  // The batch does not interpret these settings: each is handed to `run` through its flag.
  const std::vector<std::pair<const std::optional<std::string>*, std::string>> settings{
      {&config.traffic, "--traffic"}, {&config.backend, "--backend"}};
  std::vector<std::string> out;
  for (const auto& [value, flag] : settings) {
    if (!*value) continue;
    if (!run_flags.count(flag))
      throw OrchError(fmt::format("a parameter set asks for {} \"{}\", but `orchestrator run` has no {} option",
                                  flag.substr(2), **value, flag));
    out.push_back(flag);
    out.push_back(**value);
  }
  return out;
}

std::vector<std::string> run_command_line(const BatchOptions& o, const PlannedRun& run, const fs::path& run_dir,
                                          const fs::path& scenario_file) {
  const SumoConfig& cfg = run.set.sumo_config;
  std::vector<std::string> argv{o.orchestrator.string(), "run", scenario_file.string(),
                                "--out", run_dir.string(), "--seed", std::to_string(run.set.seed.value_or(42)),
                                "--step", fmt::format("{}", cfg.step)};
  if (cfg.max_time) {
    argv.emplace_back("--max-time");
    argv.push_back(fmt::format("{}", *cfg.max_time));
  }
  argv.emplace_back("-q");
  for (const auto& d : o.map_dirs) {
    argv.emplace_back("--maps");
    argv.push_back(d);
  }
  if (!o.catalog.empty()) {
    argv.emplace_back("--catalog");
    argv.push_back(o.catalog);
  }
  for (auto& f : pass_through_flags(cfg, o.run_flags)) argv.push_back(std::move(f));
  if (o.ssm) argv.emplace_back("--ssm");
  argv.insert(argv.end(), o.run_args.begin(), o.run_args.end());
  return argv;
}

QueueOutcome execute_planned_runs(const BatchOptions& o, const BatchPlan& plan, const std::vector<std::size_t>& tasks,
                                  const fs::path& out, std::size_t already_done) {
  std::ostream& msg = *o.out_stream;
  const auto groups = fork_groups(plan, tasks, !o.no_fork, *o.jobs);
  std::vector<std::size_t> group_tasks;
  for (std::size_t g = 0; g < groups.size(); ++g) group_tasks.push_back(g);
  // The runs of each group still to run in its next attempt.
  std::vector<std::vector<std::size_t>> attempt_runs = groups;
  if (groups.size() < tasks.size())
    msg << fmt::format("batch: {} runs share their common prefix in {} group(s) (docs/forking.md)\n", tasks.size(),
                       groups.size());

  Progress progress(msg, o.terminal, already_done + tasks.size(), already_done);
  std::map<std::size_t, ExecutionRecord> records;
  std::size_t attempt_runs_size = 1;
  const int max_attempts = 1 + std::max(0, *o.retries);
  QueueCallbacks callbacks;
  auto prepare_run = [&](std::size_t task, int attempt) {
    const PlannedRun& run = plan.runs[task];
    const fs::path dir = out / "runs" / run.id;
    prepare_run_dir(dir, attempt);
    const PlannedLogical& pl = plan.logicals[run.logical_index];
    std::vector<std::string> argv;
    if (pl.variation) {
      // The referenced scenario as it is (its catalogs and road are relative to it), with
      // the set's values as --param.
      argv = run_command_line(o, run, dir, pl.logical.template_file);
      for (auto& a : variation_run_arguments(*pl.variation, run.set)) argv.push_back(std::move(a));
    } else {
      const std::string bound_file = bound_file_name(pl.logical.template_file);
      for (const auto& f : bound_run_files(pl.logical, *pl.template_doc, run.set))
        write_file_atomically(dir / f.name, f.text);
      argv = run_command_line(o, run, dir, dir / bound_file);
    }
    ExecutionRecord& rec = records[task];
    rec.command = argv;
    rec.executed_at = utc_timestamp();
    return Launch{argv, dir / "child.log"};
  };
  // A group's attempt: its first run's command with the others as --fork-with/--fork-out.
  callbacks.prepare = [&](std::size_t group, int attempt) {
    const auto& runs = attempt_runs[group];
    Launch launch = prepare_run(runs.front(), attempt);
    for (std::size_t k = 1; k < runs.size(); ++k) {
      const Launch other = prepare_run(runs[k], attempt);
      const auto& a = other.argv;
      // run FILE --out DIR ...: the other's file and folder, and (a variation) its --param values.
      launch.argv.insert(launch.argv.end(), {"--fork-with", a[2], "--fork-out", a[4]});
      for (std::size_t w = 5; w + 1 < a.size(); ++w)
        if (a[w] == "--param") launch.argv.insert(launch.argv.end(), {"--fork-param", fmt::format("{}:{}", k, a[++w])});
    }
    if (o.fork_at && runs.size() > 1) launch.argv.insert(launch.argv.end(), {"--fork-at", o.fork_at->text()});
    if (!o.wrapper.empty()) launch.argv.insert(launch.argv.begin(), o.wrapper);
    for (const auto r : runs) records[r].command = launch.argv;
    return launch;
  };
  auto run_ended = [&](std::size_t task, int attempt, const ChildExit& exit, const std::string& start_error) {
    const PlannedRun& run = plan.runs[task];
    const fs::path dir = out / "runs" / run.id;
    ExecutionRecord& rec = records[task];
    // A group's process exits with the worst verdict of its runs: each run is judged by its own.
    ChildExit own = exit;
    if (attempt_runs_size > 1 && !exit.signal && !exit.timed_out && exit.exit_code && *exit.exit_code >= 0 &&
        *exit.exit_code <= 2)
      own.exit_code = verdict_exit_code(dir / "result.json").value_or(*exit.exit_code);
    Attempt a = judge_attempt(own, start_error, dir / "result.json", o.timeout_s);
    a.number = attempt;
    a.started_at = rec.executed_at;
    rec.attempts.push_back(a);
    if (should_retry(a, max_attempts)) {
      keep_attempt_logs(dir, attempt);
      progress.note(fmt::format("retry   {}: attempt {} of {} after: {}", label_of(run), attempt + 1, max_attempts, a.reason));
      return true;
    }
    rec.execution_uuid = random_uuid();
    rec.fork = nullptr;
    if (fs::exists(dir / "fork.json")) {
      try {
        rec.fork = ordered_json::parse(read_file(dir / "fork.json"));
      } catch (const std::exception&) {
        // A fork.json that does not read says nothing; the run's own files decide.
      }
    }
    // Last and atomically: from here on the run counts as done, and never before.
    write_file_atomically(execution_trace_path(out, run.id),
                          execution_trace_text(run, plan.logicals[run.logical_index], rec));
    double wall = 0;
    for (const auto& x : rec.attempts) wall += x.wall_time_s;
    progress.run_finished(a.verdict, label_of(run), a.verdict == "success" ? "" : a.reason, wall);
    records.erase(task);
    return false;
  };
  callbacks.ended = [&](std::size_t group, int attempt, const ChildExit& exit, const std::string& start_error) {
    std::vector<std::size_t> again;
    const auto runs = attempt_runs[group];
    attempt_runs_size = runs.size();
    const fs::path first = out / "runs" / plan.runs[runs.front()].id;
    for (const auto r : runs) {
      // One child.log per group: each run folder gets its copy.
      const fs::path dir = out / "runs" / plan.runs[r].id;
      std::error_code ec;
      if (dir != first) fs::copy_file(first / "child.log", dir / "child.log", fs::copy_options::overwrite_existing, ec);
    }
    for (const auto r : runs)
      if (run_ended(r, attempt, exit, start_error)) again.push_back(r);
    attempt_runs[group] = again;
    return !again.empty();
  };
  callbacks.tick = [&] { progress.tick(); };
  const QueueOutcome outcome = run_queue(group_tasks, QueueOptions{*o.jobs, o.timeout_s, 0.5}, callbacks);
  progress.close();
  // Interrupted: the runs of the groups not finished (the callers count runs, not groups).
  QueueOutcome runs_outcome{outcome.interrupted, {}};
  for (const auto g : outcome.unfinished)
    runs_outcome.unfinished.insert(runs_outcome.unfinished.end(), attempt_runs[g].begin(), attempt_runs[g].end());
  std::sort(runs_outcome.unfinished.begin(), runs_outcome.unfinished.end());
  return runs_outcome;
}

int run_batch(const BatchOptions& given) {
  const auto session_start = std::chrono::steady_clock::now();
  BatchOptions o = given;
  std::ostream& msg = *o.out_stream;
  const fs::path out = fs::absolute(o.out).lexically_normal();
  std::optional<Manifest> manifest;
  if (o.resume) {
    if (!o.inputs.empty()) throw OrchError("--resume takes the inputs from DIR/batch.json: give no input files");
    if (o.shard) throw OrchError("--resume keeps the batch's own --shard: give none");
    manifest = read_manifest(out);
    o.inputs = manifest->inputs;
    o.shard = manifest->shard;
    apply_manifest_defaults(o, *manifest);
  } else if (fs::exists(manifest_path(out))) {
    throw OrchError(fmt::format("{} holds a batch already: continue it with --resume {}, or choose another --out",
                                out.string(), out.string()));
  }
  if (!o.jobs) o.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (!o.timeout_s) o.timeout_s = kDefaultTimeout;
  if (!o.retries) o.retries = kDefaultRetries;

  // Inputs are checked before the folder is touched: a batch that cannot start leaves none.
  BatchPlan plan = plan_batch(o.inputs, o.shard);
  if (o.fork) use_one_seed_per_logical(plan);
  if (o.fork_at) check_fork_event(plan, *o.fork_at);
  for (const auto& run : plan.runs) pass_through_flags(run.set.sumo_config, o.run_flags);
  fs::create_directories(out / "runs");
  fs::create_directories(out / "executions");
  const FolderLock lock(out);
  if (manifest) verify_unchanged(*manifest, plan);
  else write_file_atomically(manifest_path(out), manifest_text(plan, options_json(o)));

  const std::vector<bool> done = find_done(out, plan, msg);
  std::vector<std::size_t> tasks;
  for (std::size_t i = 0; i < plan.runs.size(); ++i)
    if (!done[i]) tasks.push_back(i);
  msg << fmt::format("batch: {} runs{}, {} to run, {} at a time, timeout {:g} s, into {}\n", plan.runs.size(),
                     plan.shard ? fmt::format(" (shard {} of {} in all)", plan.shard->text(), plan.total_runs) : "",
                     tasks.size(), *o.jobs, *o.timeout_s, out.string());

  const QueueOutcome outcome = execute_planned_runs(o, plan, tasks, out, plan.runs.size() - tasks.size());

  BatchReport report = collect_report({out});
  report.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - session_start).count();
  msg << "\n" << write_reports(report, out);
  msg << fmt::format("\nresults: {} (summary.json, junit.xml, summary.txt)\n", out.string());
  if (outcome.interrupted) {
    msg << fmt::format("batch: interrupted; {} run(s) not done: continue with `orchestrator batch --resume {}`\n",
                       outcome.unfinished.size(), out.string());
    return 3;
  }
  // A shard answers for its own runs; the other shards' runs are merged later.
  return batch_exit_code(report.planned_totals());
}

}  // namespace orch::batch
