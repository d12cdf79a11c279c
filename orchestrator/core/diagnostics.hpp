#pragma once
// Problems found in user input, each tied to the place in the file it came from.
#include <string>
#include <vector>

namespace orch {

struct SourceLocation {
  std::string file;     // path as the user gave it
  std::string pointer;  // RFC 6901 JSON pointer, "" = whole document
  int line = 0;         // 1-based; 0 = unknown
};

enum class Severity { Error, Warning };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLocation where;
  std::string message;
  // "file:line: error: /json/pointer: message" (compiler style, so editors can jump to it)
  [[nodiscard]] std::string format() const;
};

class Diagnostics {
 public:
  void error(SourceLocation where, std::string message);
  void warning(SourceLocation where, std::string message);
  void append(const Diagnostics& other);
  [[nodiscard]] bool has_errors() const { return errors_ > 0; }
  [[nodiscard]] int error_count() const { return errors_; }
  [[nodiscard]] int warning_count() const { return static_cast<int>(items_.size()) - errors_; }
  [[nodiscard]] const std::vector<Diagnostic>& items() const { return items_; }
  // All messages, one per line, errors and warnings in the order found.
  [[nodiscard]] std::string format() const;

 private:
  std::vector<Diagnostic> items_;
  int errors_ = 0;
};

}  // namespace orch
