#include "core/output_file.hpp"

#include "core/errors.hpp"

namespace orch {

OutputFile::OutputFile(const std::filesystem::path& path, std::string_view first_line)
    : file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw OrchError("cannot write " + path.string());
  if (!first_line.empty()) line(first_line);
}

void OutputFile::flush() {
  std::fflush(file_.get());
  steps_since_flush_ = 0;
}

}  // namespace orch
