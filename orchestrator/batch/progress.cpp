#include "batch/progress.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/checked_numeric.hpp"

namespace orch::batch {

Progress::Progress(std::ostream& out, bool terminal, std::size_t total, std::size_t already_done)
    : out_(out), terminal_(terminal), total_(total), done_(already_done), start_(std::chrono::steady_clock::now()) {
  if (terminal_) redraw();
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string Progress::clock(double seconds) {
  const auto s = clamped_round<long long>(seconds, 0, 1LL << 40);  // NaN (no estimate yet) shows 0:00
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

std::string Progress::bar_line() const {
  constexpr int kWidth = 30;
  const double fraction = total_ == 0 ? 1.0 : static_cast<double>(done_) / static_cast<double>(total_);
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '.');
  std::string eta = "--";
  if (done_now_ > 0) {
    const double per_run = elapsed() / static_cast<double>(done_now_);
    eta = clock(per_run * static_cast<double>(total_ - done_));
  }
  return fmt::format("[{}] {}/{}  failures {}  errors {}  elapsed {}  ETA {}", bar, done_, total_, failures_, errors_,
                     clock(elapsed()), eta);
}

void Progress::redraw() {
  out_ << "\r\033[K" << bar_line() << std::flush;
  bar_shown_ = true;
}

void Progress::run_finished(const std::string& verdict, const std::string& label, const std::string& reason,
                            double wall_s) {
  ++done_;
  ++done_now_;
  if (verdict == "failure") ++failures_;
  if (verdict == "error") ++errors_;
  const std::string line = fmt::format("[{}/{}] {:<7} {} ({:.1f} s){}{}", done_, total_, verdict, label, wall_s,
                                       reason.empty() ? "" : ": ", reason);
  if (!terminal_) {
    out_ << line << "\n" << std::flush;
    return;
  }
  // On a terminal only what needs a look stays on screen; successes just move the bar.
  if (verdict != "success") out_ << "\r\033[K" << line << "\n";
  redraw();
}

void Progress::note(const std::string& line) {
  if (!terminal_) {
    out_ << line << "\n" << std::flush;
    return;
  }
  out_ << "\r\033[K" << line << "\n";
  redraw();
}

void Progress::tick() {
  if (terminal_) redraw();
}

void Progress::close() {
  if (terminal_ && bar_shown_) {
    redraw();
    out_ << "\n" << std::flush;
    bar_shown_ = false;
  }
}

}  // namespace orch::batch
