#include "core/diagnostics.hpp"

#include <fmt/format.h>

#include "core/utf8.hpp"

namespace orch {

std::string Diagnostic::format() const {
  const char* kind = severity == Severity::Error ? "error" : "warning";
  std::string place = where.file;
  if (where.line > 0) place += fmt::format(":{}", where.line);
  const std::string pointer = where.pointer.empty() ? "/" : where.pointer;
  // The file name (argv) and the message may quote bytes of the input: keep the text valid.
  return valid_utf8(fmt::format("{}: {}: {}: {}", place, kind, pointer, message));
}

void Diagnostics::error(SourceLocation where, std::string message) {
  items_.push_back({Severity::Error, std::move(where), std::move(message)});
  ++errors_;
}

void Diagnostics::warning(SourceLocation where, std::string message) {
  items_.push_back({Severity::Warning, std::move(where), std::move(message)});
}

void Diagnostics::append(const Diagnostics& other) {
  for (const auto& d : other.items_) {
    items_.push_back(d);
    if (d.severity == Severity::Error) ++errors_;
  }
}

std::string Diagnostics::format() const {
  std::string out;
  for (const auto& d : items_) {
    out += d.format();
    out += '\n';
  }
  return out;
}

}  // namespace orch
