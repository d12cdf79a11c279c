#include "run/run_log.hpp"

#include <fmt/format.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "core/utf8.hpp"

namespace orch {

RunLog::RunLog(const std::filesystem::path& file, bool echo) {
  std::vector<spdlog::sink_ptr> sinks;
  sinks.push_back(std::make_shared<spdlog::sinks::basic_file_sink_st>(file.string(), true));
  if (echo) sinks.push_back(std::make_shared<spdlog::sinks::stdout_sink_st>());
  logger_ = std::make_shared<spdlog::logger>("run", sinks.begin(), sinks.end());
  logger_->set_pattern("%v");  // lines carry simulation time, not wall-clock time
  logger_->flush_on(spdlog::level::info);
}

RunLog::~RunLog() { flush(); }

// Lines may quote input bytes (file names, parse errors): the log stays valid UTF-8.
void RunLog::at(double sim_time, const std::string& text) { logger_->info("t={:9.3f}  {}", sim_time, valid_utf8(text)); }

void RunLog::note(const std::string& text) { logger_->info("{}", valid_utf8(text)); }

void RunLog::flush() { logger_->flush(); }

}  // namespace orch
