#include "run/fork_group.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "run/run_session.hpp"
#include "run/same_commands.hpp"

namespace orch {

namespace {

// SUMO's command line less its log file (each run names its own sumo.log): runs whose
// settings give the same line can share one SUMO.
std::vector<std::string> shared_arguments(const SimulatorConfig& config) {
  std::vector<std::string> args = sumo_arguments(config);
  for (std::size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "--log") args.erase(args.begin() + static_cast<std::ptrdiff_t>(i), args.begin() + static_cast<std::ptrdiff_t>(i) + 2);
  return args;
}

// What one run did before it had SUMO to itself: written to its fork.json.
struct Sharing {
  double own_from_s = 0;                // SUMO time at which this run's process began simulating
  std::optional<std::string> forked_from;  // the run folder that kept the shared SUMO
  long long shared_steps = 0;
  std::string warning;  // --fork-at: the run parted from others before the requested time
};

class Group {
 public:
  Group(const std::vector<RunRequest>& requests, Simulator& sim, std::optional<ForkCheckpoint> fork_at)
      : reqs_(requests), sim_(sim), fork_at_(std::move(fork_at)) {
    for (const auto& r : requests) runs_.push_back(std::make_unique<RunSession>(r, sim));
    sharing_.resize(requests.size());
  }

  void run() {
    std::vector<std::size_t> live;
    std::vector<SimulatorConfig> configs(reqs_.size());
    for (std::size_t i = 0; i < reqs_.size(); ++i)
      if (runs_[i]->open(configs[i])) live.push_back(i);
      else end_run(i);
    live = split(live, [&](std::size_t i) { return fmt::format("{}", fmt::join(shared_arguments(configs[i]), " ")); },
                 0, 0);
    if (!live.empty()) run_class(live, configs[live.front()]);
    finish_process();
  }

 private:
  void run_class(std::vector<std::size_t> live, const SimulatorConfig& config) {
    try {
      sim_.start(config);
    } catch (...) {
      for (auto i : live) runs_[i]->fail();
    }
    std::erase_if(live, [&](std::size_t i) { return !runs_[i]->started() && end_run(i); });
    std::map<std::size_t, std::vector<sim::Command>> commands;
    for (auto i : live)
      if (auto c = runs_[i]->first_commands()) commands[i] = std::move(*c);
    std::erase_if(live, [&](std::size_t i) { return !commands.count(i) && end_run(i); });
    live = split_by_commands(live, commands, 0, 0);
    live = checkpoint(live, 0, 0);
    long long steps = 0;
    while (!live.empty()) {
      if (!simulate(live, commands[live.front()])) break;
      ++steps;
      for (auto i : live) sharing_[i].shared_steps = steps;
      std::erase_if(live, [&](std::size_t i) { return runs_[i]->take(snapshot_) && end_run(i); });
      commands.clear();
      for (auto i : live)
        if (auto c = runs_[i]->next_commands(snapshot_)) commands[i] = std::move(*c);
      std::erase_if(live, [&](std::size_t i) { return !commands.count(i) && end_run(i); });
      live = split_by_commands(live, commands, snapshot_.time, steps);
      live = checkpoint(live, snapshot_.time, steps);
    }
  }

  // --fork-at: at the first step at or after the requested time, or at the first step after
  // which a run of the class has had the requested event (its commands for the next step
  // given), one process per variant.
  std::vector<std::size_t> checkpoint(const std::vector<std::size_t>& live, double time, long long steps) {
    if (!fork_at_ || checkpoint_s_ || before_checkpoint(live, time)) return live;
    checkpoint_s_ = time;
    return split(live, [](std::size_t i) { return std::to_string(i); }, time, steps);
  }

  // The class has not come to the requested checkpoint yet (and it was requested).
  bool before_checkpoint(const std::vector<std::size_t>& live, double time) const {
    if (!fork_at_ || checkpoint_s_) return false;
    if (fork_at_->time_s) return time < *fork_at_->time_s - 1e-9;
    return std::none_of(live.begin(), live.end(), [&](std::size_t i) { return runs_[i] && runs_[i]->reached(fork_at_->event); });
  }

  // Applies the class's commands, advances SUMO one step and reads it (every run of the
  // class tracks the same actors: split_by_commands makes sure). A failure ends every run
  // of the class with verdict error, as it would each run alone.
  bool simulate(std::vector<std::size_t>& live, const std::vector<sim::Command>& commands) {
    try {
      sim_.apply(commands);
      const auto before = std::chrono::steady_clock::now();
      sim_.advance();
      const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
      for (auto i : live) runs_[i]->add_step_time(took);
      snapshot_ = sim_.read(runs_[live.front()]->tracked());
      return true;
    } catch (...) {
      for (auto i : live) runs_[i]->fail();
    }
    for (auto i : live) end_run(i);
    live.clear();
    return false;
  }

  std::vector<std::size_t> split_by_commands(const std::vector<std::size_t>& live,
                                             const std::map<std::size_t, std::vector<sim::Command>>& commands,
                                             double time, long long steps) {
    // Classes by equal commands and equal tracked actors, in the order of their first run.
    std::vector<std::size_t> leaders;
    std::map<std::size_t, std::size_t> leader_of;
    for (auto i : live) {
      std::optional<std::size_t> found;
      for (auto l : leaders)
        if (same_commands(commands.at(l), commands.at(i)) && same_tracked(runs_[l]->tracked(), runs_[i]->tracked())) {
          found = l;  // the classes are disjoint: no other leader can match
          break;
        }
      if (!found) leaders.push_back(i);
      leader_of[i] = found.value_or(i);
    }
    if (leaders.size() > 1 && before_checkpoint(live, time))
      for (auto i : live)
        if (sharing_[i].warning.empty())
          sharing_[i].warning = fmt::format(
              "--fork-at {}: its commands differed from those of {} at t = {:g} s, before the requested {} (the "
              "parameters act earlier): the variants parted there, so that its outputs stay exactly those of its run "
              "from t = 0",
              fork_at_->time_s ? fork_at_->text() + " s" : fork_at_->event,
              reqs_[leaders.front() == leader_of[i] ? leaders[1] : leaders.front()].out_dir.string(), time,
              fork_at_->time_s ? "time" : "event");
    return split(live, [&](std::size_t i) { return std::to_string(leader_of[i]); }, time, steps);
  }

  // Keeps the class of the first run in this process; each other class continues in a
  // forked child, which this process waits for (one process runs at a time).
  template <typename Key>
  std::vector<std::size_t> split(const std::vector<std::size_t>& live, Key key, double time, long long steps) {
    std::vector<std::string> keys;
    std::map<std::string, std::vector<std::size_t>> classes;
    for (auto i : live) {
      const std::string k = key(i);
      if (!classes.count(k)) keys.push_back(k);
      classes[k].push_back(i);
    }
    if (keys.size() <= 1) return live;
    const std::vector<std::size_t> kept = classes[keys.front()];
    for (std::size_t c = 1; c < keys.size(); ++c) {
      const auto& other = classes[keys[c]];
      std::cout.flush();
      std::cerr.flush();
      std::fflush(nullptr);
      const pid_t pid = ::fork();
      if (pid == 0) {
        // The child: the other runs belong to other processes (never flushed here).
        for (auto i : live)
          if (std::find(other.begin(), other.end(), i) == other.end()) abandon(i);
        for (auto i : other) {
          sharing_[i].own_from_s = time;
          sharing_[i].forked_from = reqs_[kept.front()].out_dir.string();
        }
        child_ = true;
        return other;
      }
      if (pid < 0) {
        // No fork: these runs end as errors, the others go on.
        for (auto i : other) {
          try {
            throw SimulationError(fmt::format("could not fork the process for a variant at t={:.3f} s", time));
          } catch (...) {
            runs_[i]->fail();
          }
          end_run(i);
        }
        continue;
      }
      for (auto i : other) abandon(i);
      int status = 0;
      ::waitpid(pid, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        std::cerr << fmt::format("orchestrator: the process of a forked variant (from t={:.3f} s, step {}) ended "
                                 "abnormally (status {})\n",
                                 time, steps, status);
    }
    return kept;
  }

  // A run handed to another process: never finished (or flushed) here.
  void abandon(std::size_t i) {
    static auto* abandoned = new std::vector<std::unique_ptr<RunSession>>();
    if (runs_[i]) abandoned->push_back(std::move(runs_[i]));
  }

  bool end_run(std::size_t i) {
    if (!runs_[i]) return true;
    results_[i] = runs_[i]->finish(false);
    write_sharing(i, results_[i].sim_time);
    runs_[i].reset();  // its files closed now
    return true;
  }

  void write_sharing(std::size_t i, double sim_time) {
    const Sharing& s = sharing_[i];
    nlohmann::ordered_json j;
    j["forked"] = s.forked_from.has_value();
    j["own_from_s"] = s.own_from_s;
    j["forked_from"] = s.forked_from ? nlohmann::ordered_json(*s.forked_from) : nlohmann::ordered_json(nullptr);
    j["simulated_s"] = sim_time;
    j["saved_s"] = s.own_from_s;
    j["process"] = static_cast<long long>(::getpid());
    if (fork_at_ && fork_at_->time_s) j["fork_at_s"] = *fork_at_->time_s;
    if (fork_at_ && !fork_at_->time_s) j["fork_at_event"] = fork_at_->event;
    // Where this run's process took the checkpoint (null: its runs ended before it).
    if (fork_at_) j["checkpoint_s"] = checkpoint_s_ ? nlohmann::ordered_json(*checkpoint_s_) : nlohmann::ordered_json(nullptr);
    if (s.warning.empty() && fork_at_ && !fork_at_->time_s && !checkpoint_s_)
      j["warning"] = fmt::format("--fork-at {}: the event did not happen in the runs of its process before it ended: "
                                 "no checkpoint (its outputs are those of its run from t = 0)", fork_at_->event);
    if (!s.warning.empty()) j["warning"] = s.warning;
    write_file_atomically(reqs_[i].out_dir / "fork.json", j.dump(2) + "\n");
  }

  void finish_process() {
    try {
      sim_.close();
    } catch (...) {
      // Closing a failed SUMO: nothing left to release.
    }
    if (!child_) return;
    for (auto& r : runs_) r.reset();
    std::cout.flush();
    std::fflush(nullptr);
    std::_Exit(0);  // the parent goes on with its own runs; no exit handlers of its state here
  }

  const std::vector<RunRequest>& reqs_;
  Simulator& sim_;
  std::vector<std::unique_ptr<RunSession>> runs_;
  std::vector<Sharing> sharing_;
  std::map<std::size_t, RunResult> results_;
  sim::WorldSnapshot snapshot_;
  bool child_ = false;
  std::optional<ForkCheckpoint> fork_at_;
  std::optional<double> checkpoint_s_;  // SUMO time at which this process took the checkpoint

 public:
  [[nodiscard]] const std::map<std::size_t, RunResult>& results() const { return results_; }
};

std::optional<Verdict> verdict_in(const std::filesystem::path& result_file, std::string& reason) {
  try {
    std::ifstream in(result_file);
    const auto j = nlohmann::json::parse(in);
    reason = j.value("reason", "");
    const std::string v = j.value("verdict", "");
    if (v == "success") return Verdict::Success;
    if (v == "failure") return Verdict::Failure;
    if (v == "error") return Verdict::Error;
  } catch (const std::exception&) {
    // Missing or unreadable: the run's process did not finish it.
  }
  return std::nullopt;
}

}  // namespace

std::string fork_refusal(const std::vector<RunRequest>& requests, const std::string& backend) {
  if (backend != "libsumo")
    return "the " + backend + " backend runs SUMO in another process, which cannot be forked (and SUMO 1.15's "
           "saved states are not exact: docs/forking.md)";
  for (const auto& r : requests) {
    if (r.ego_link) return "an external ego plug-in drives the ego: its state cannot be forked";
    if (r.reference_run) return "--reference-run runs a second simulation per run";
  }
  return {};
}

void write_unforked(const RunRequest& request, const std::string& why) {
  nlohmann::ordered_json j;
  j["forked"] = false;
  j["own_from_s"] = 0.0;
  j["forked_from"] = nullptr;
  j["saved_s"] = 0.0;
  j["not_forked"] = why;
  j["process"] = static_cast<long long>(::getpid());
  write_file_atomically(request.out_dir / "fork.json", j.dump(2) + "\n");
}

std::vector<RunResult> run_fork_group(const std::vector<RunRequest>& requests, Simulator& simulator,
                                      const std::optional<ForkCheckpoint>& fork_at) {
  Group group(requests, simulator, fork_at);
  group.run();
  std::vector<RunResult> out(requests.size());
  for (std::size_t i = 0; i < requests.size(); ++i) {
    if (const auto it = group.results().find(i); it != group.results().end()) {
      out[i] = it->second;
      continue;
    }
    std::string reason;
    const auto v = verdict_in(requests[i].out_dir / "result.json", reason);
    out[i].verdict = v.value_or(Verdict::Error);
    out[i].reason = v ? reason : "its forked process wrote no result.json";
  }
  return out;
}

}  // namespace orch
