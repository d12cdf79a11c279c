#pragma once
// A parsed JSON file that can tell on which line every value starts, so that every message
// about it can name file, line and JSON pointer. nlohmann::json parses the values; a SAX
// pass over the same text records the lines (nlohmann 3.11 keeps no positions) when the
// first line is asked for.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>

#include "core/diagnostics.hpp"
#include "json/line_index.hpp"

namespace orch {

// Limits far above any real input, so that cost stays bounded by what a file can hold:
// nesting (scenarios nest about 8 deep; recursion in the readers must not exhaust the
// stack) and size (the line index counts in 32 bits).
inline constexpr std::size_t kMaxJsonDepth = 256;
inline constexpr std::size_t kMaxJsonBytes = std::size_t{1} << 31;

class JsonDocument {
 public:
  JsonDocument() = default;
  JsonDocument(const JsonDocument&) = default;
  JsonDocument(JsonDocument&&) noexcept = default;
  JsonDocument& operator=(const JsonDocument&) = default;
  JsonDocument& operator=(JsonDocument&&) noexcept = default;
  // Empties the tree leaves first (release_tree): nlohmann's own destructor first moves every
  // child of a container into a vector of its own, a second copy of a large array.
  ~JsonDocument();

  // Reads and parses `path`. Throws ScenarioError (with line) on unreadable or invalid JSON,
  // including duplicate keys, which nlohmann would otherwise silently collapse, nesting
  // deeper than kMaxJsonDepth and text longer than kMaxJsonBytes.
  static JsonDocument load(const std::string& path);
  static JsonDocument parse(std::string text, const std::string& path_for_messages);
  // A value tree read from another format (a YAML file), with the line of every pointer as
  // that format's parser knew it: the same readers and messages serve both formats.
  static JsonDocument from_tree(nlohmann::json root, const std::string& path,
                                std::unordered_map<std::string, int> lines);

  [[nodiscard]] const nlohmann::json& root() const { return root_; }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& text() const { return text_; }
  // Line where the value at `pointer` starts; for a pointer that does not exist, the line
  // of its nearest existing ancestor.
  [[nodiscard]] int line_of(const std::string& pointer) const;
  [[nodiscard]] SourceLocation where(const std::string& pointer) const {
    return {path_, pointer, line_of(pointer)};
  }

 private:
  const LineIndex& lines() const;

  std::string path_;
  std::string text_;
  nlohmann::json root_;
  // Built once, on the first line_of (not thread-safe: a document is read by one thread);
  // shared by copies.
  mutable std::shared_ptr<const LineIndex> lines_;
};

// Destroys a value tree without nlohmann's destructor's flattening copy (every child of an
// array or object moved into a vector that grows by doubling: a 100 MB file's tree held
// twice more at the end of a run; docs/hardening.md). Children are emptied before their
// parents; the recursion is as deep as the tree (at most kMaxJsonDepth for a parsed text).
void release_tree(nlohmann::json& value) noexcept;

// Appends one reference token to a JSON pointer, escaping '~' and '/' (RFC 6901).
std::string json_pointer_child(const std::string& parent, const std::string& key);
std::string json_pointer_child(const std::string& parent, std::size_t index);

}  // namespace orch
