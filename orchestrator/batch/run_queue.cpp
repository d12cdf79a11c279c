#include "batch/run_queue.hpp"

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <deque>

namespace orch::batch {

namespace {

struct Running {
  std::size_t task = 0;
  int attempt = 1;
  ChildProcess child;
};

// Blocks SIGCHLD, SIGINT and SIGTERM for the queue's lifetime (so that they are only
// received through sigtimedwait) and restores the previous mask afterwards.
class BlockedSignals {
 public:
  BlockedSignals() {
    sigemptyset(&set_);
    sigaddset(&set_, SIGCHLD);
    sigaddset(&set_, SIGINT);
    sigaddset(&set_, SIGTERM);
    ::sigprocmask(SIG_BLOCK, &set_, &old_);
  }
  ~BlockedSignals() {
    // Drop our own pending SIGCHLDs, but let a pending SIGINT/SIGTERM take effect later.
    timespec zero{0, 0};
    sigset_t chld;
    sigemptyset(&chld);
    sigaddset(&chld, SIGCHLD);
    while (::sigtimedwait(&chld, nullptr, &zero) > 0) {
    }
    ::sigprocmask(SIG_SETMASK, &old_, nullptr);
  }
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;

  // Waits up to `seconds`; returns the signal received or 0.
  int wait(double seconds) const {
    // At most a day per wait (callers loop); NaN waits not at all.
    const double s = std::isnan(seconds) ? 0.0 : std::clamp(seconds, 0.0, 86400.0);
    timespec ts{static_cast<time_t>(s), static_cast<long>((s - std::floor(s)) * 1e9)};
    const int sig = ::sigtimedwait(&set_, nullptr, &ts);
    return sig > 0 ? sig : 0;
  }

 private:
  sigset_t set_{};
  sigset_t old_{};
};

}  // namespace

QueueOutcome run_queue(const std::vector<std::size_t>& tasks, const QueueOptions& options,
                       const QueueCallbacks& callbacks) {
  const BlockedSignals signals;
  std::deque<std::pair<std::size_t, int>> pending;  // (task, attempt)
  for (std::size_t t : tasks) pending.emplace_back(t, 1);
  std::vector<Running> running;
  QueueOutcome outcome;
  const std::size_t jobs = static_cast<std::size_t>(std::max(1, options.jobs));

  const auto finish = [&](std::size_t task, int attempt, const ChildExit& exit, const std::string& error) {
    if (callbacks.ended(task, attempt, exit, error)) pending.emplace_front(task, attempt + 1);
  };

  while (!pending.empty() || !running.empty()) {
    while (running.size() < jobs && !pending.empty() && !outcome.interrupted) {
      const auto [task, attempt] = pending.front();
      pending.pop_front();
      try {
        const Launch launch = callbacks.prepare(task, attempt);
        running.push_back({task, attempt, ChildProcess::start(launch.argv, launch.log_file)});
      } catch (const std::exception& e) {
        ChildExit failed;
        failed.exit_code = 127;
        finish(task, attempt, failed, e.what());
      }
    }
    if (running.empty()) {
      if (outcome.interrupted) break;
      continue;
    }

    // Sleep until a child ends, a signal arrives, the next deadline or the next tick.
    double wait_s = options.tick_s;
    if (options.timeout_s)
      for (const auto& r : running) wait_s = std::min(wait_s, *options.timeout_s - r.child.elapsed_s());
    const int sig = signals.wait(wait_s);
    if ((sig == SIGINT || sig == SIGTERM) && !outcome.interrupted) {
      outcome.interrupted = true;
      for (auto& r : running) {
        r.child.kill_tree(false);
        outcome.unfinished.push_back(r.task);
      }
      for (const auto& [task, attempt] : pending) outcome.unfinished.push_back(task);
      pending.clear();
    }

    for (auto it = running.begin(); it != running.end();) {
      if (options.timeout_s && it->child.elapsed_s() >= *options.timeout_s) it->child.kill_tree(true);
      if (auto exit = it->child.poll()) {
        const std::size_t task = it->task;
        const int attempt = it->attempt;
        it = running.erase(it);
        if (!outcome.interrupted) finish(task, attempt, *exit, {});
      } else {
        ++it;
      }
    }
    if (callbacks.tick) callbacks.tick();
  }
  std::sort(outcome.unfinished.begin(), outcome.unfinished.end());
  outcome.unfinished.erase(std::unique(outcome.unfinished.begin(), outcome.unfinished.end()), outcome.unfinished.end());
  return outcome;
}

}  // namespace orch::batch
