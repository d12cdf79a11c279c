#pragma once
// The readable account of a run: one line per scene transition, action and notable event,
// each with its simulation time, to run.log and (unless quiet) the terminal.
#include <filesystem>
#include <memory>
#include <string>

namespace spdlog {
class logger;
}

namespace orch {

class RunLog {
 public:
  RunLog(const std::filesystem::path& file, bool echo);
  ~RunLog();
  void at(double sim_time, const std::string& text);  // "t=  12.350  text"
  void note(const std::string& text);                 // lines without a time (setup, summary)
  void flush();

 private:
  std::shared_ptr<spdlog::logger> logger_;
};

}  // namespace orch
