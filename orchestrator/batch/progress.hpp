#pragma once
// What a batch prints while it runs. On a terminal: a live progress bar (done/total,
// failures and errors so far, elapsed, ETA) with each failure or error printed above it.
// Elsewhere (CI logs, files): one line per finished run, nothing redrawn.
#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace orch::batch {

class Progress {
 public:
  // `already_done`: runs a resumed batch finds finished; they count as done but not
  // towards the ETA, which is measured on this session's runs only.
  Progress(std::ostream& out, bool terminal, std::size_t total, std::size_t already_done);
  void run_finished(const std::string& verdict, const std::string& label, const std::string& reason, double wall_s);
  // A line that is not a finished run (a retry): printed above the bar, or as is.
  void note(const std::string& line);
  void tick();
  void close();

  // "1:05" / "1:02:03"
  static std::string clock(double seconds);
  // The bar line without "\r": for tests and for the terminal.
  [[nodiscard]] std::string bar_line() const;

 private:
  [[nodiscard]] double elapsed() const;
  void redraw();

  std::ostream& out_;
  bool terminal_;
  std::size_t total_;
  std::size_t done_;
  std::size_t done_now_ = 0;  // finished in this session
  std::size_t failures_ = 0;
  std::size_t errors_ = 0;
  std::chrono::steady_clock::time_point start_;
  bool bar_shown_ = false;
};

}  // namespace orch::batch
