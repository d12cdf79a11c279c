#pragma once
// A text output the run writes as it goes (trace.csv, metrics.csv, counts.csv,
// background.csv, result.jsonl): opened once, written with fmt, flushed every
// `flush_every` lines written through end_step() so that a crash keeps what was simulated,
// closed by its owner. One class instead of a hand-written FILE* in every writer.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string_view>
#include <type_traits>

#include <fmt/compile.h>
#include <fmt/format.h>

namespace orch {

class OutputFile {
 public:
  // Opens `path` for writing (an existing file is replaced) and writes `first_line` (the
  // CSV header) when not empty. Throws OrchError "cannot write PATH".
  explicit OutputFile(const std::filesystem::path& path, std::string_view first_line = {});

  template <class... Args>
  void print(fmt::format_string<Args...> format, Args&&... args) {
    fmt::print(file_.get(), format, std::forward<Args>(args)...);
  }
  // The same with FMT_COMPILE("...") formats: the per-step rows (trace.csv, counts.csv,
  // background.csv) are formatted by code generated at compile time, not by parsing the
  // format string on every row (that parsing was a third of a trace row's cost). The same
  // bytes: fmt formats each field with the same specs either way.
  template <class S, class... Args, std::enable_if_t<fmt::detail::is_compiled_string<S>::value, int> = 0>
  void print(const S& format, const Args&... args) {
    row_.clear();
    fmt::format_to(fmt::appender(row_), format, args...);
    std::fwrite(row_.data(), 1, row_.size(), file_.get());
  }
  void line(std::string_view text) { print("{}\n", text); }
  // One step written: every `every` steps the lines reach the disk.
  void end_step(int every = 200) {
    if (++steps_since_flush_ >= every) flush();
  }
  void flush();

 private:
  struct Close {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, Close> file_;
  fmt::memory_buffer row_;  // one row, reused
  int steps_since_flush_ = 0;
};

}  // namespace orch
