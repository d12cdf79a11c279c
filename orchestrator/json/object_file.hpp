#pragma once
// A JSON file whose root is one object, read key by key with the project's messages: the
// file is loaded (unreadable, not JSON: ScenarioError naming the file and line), `top()`
// reads its keys, and `finish()` reports the unknown keys and throws every error found at
// once (file, line, JSON pointer). One helper instead of the same four lines in every
// reader of a small JSON file (map manifests, waypoint files, batch files).
#include <string>
#include <utility>

#include "core/diagnostics.hpp"
#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/object_reader.hpp"

namespace orch {

class JsonObjectFile {
 public:
  // `what` names the file's kind in messages ("waypoint file").
  JsonObjectFile(const std::string& path, std::string what)
      : doc_(JsonDocument::load(path)), top_(doc_, doc_.root(), "", diags_, std::move(what)) {}
  JsonObjectFile(const JsonObjectFile&) = delete;  // top_ refers to doc_ and diags_
  JsonObjectFile& operator=(const JsonObjectFile&) = delete;

  [[nodiscard]] const JsonDocument& doc() const { return doc_; }
  [[nodiscard]] Diagnostics& diags() { return diags_; }
  [[nodiscard]] ObjectReader& top() { return top_; }

  // Unknown keys of the top object, then every error: throws ScenarioError when any.
  void finish() {
    top_.finish();
    throw_if_errors();
  }
  // Every error so far (for readers that finish nested objects themselves).
  void throw_if_errors() const {
    if (diags_.has_errors()) throw ScenarioError(diags_);
  }

 private:
  JsonDocument doc_;
  Diagnostics diags_;
  ObjectReader top_;
};

}  // namespace orch
