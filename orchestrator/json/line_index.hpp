#pragma once
// The line on which every value of a JSON text starts, found by JSON pointer. Built by one
// SAX pass in time and memory linear in the text: one flat entry per value (line, end of its
// subtree, where its key is) and the keys once; no pointer string per value (with pointers
// per value, 100,000 nested arrays took 20 GB). Pointers are only made for messages.
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace orch {

class LineIndex {
 public:
  // Throws ScenarioError naming file, pointer and line when an object repeats a key.
  // Expects text that nlohmann parses (JsonDocument checks that first).
  static LineIndex build(const std::string& text, const std::string& path_for_messages);
  // The lines another format's parser knew (a YAML file read into a JSON tree), by pointer.
  static LineIndex from_lines(std::unordered_map<std::string, int> lines);

  // Line where the value at `pointer` starts (an object member's: the line of its key); for
  // a pointer that does not exist, the line of its nearest existing ancestor.
  [[nodiscard]] int line_of(std::string_view pointer) const;

 private:
  friend class LineIndexBuilder;
  enum class Kind : std::uint8_t { Scalar, Object, Array };
  struct Entry {
    std::int32_t line = 0;
    std::uint32_t end = 0;         // one past the last entry of this value's subtree
    std::uint32_t key_offset = 0;  // an object member's key in keys_
    std::uint32_t key_size = 0;
    Kind kind = Kind::Scalar;
  };
  [[nodiscard]] std::string_view key_of(const Entry& e) const { return std::string_view(keys_).substr(e.key_offset, e.key_size); }

  std::vector<Entry> entries_;  // in document order: a value's children follow it
  std::string keys_;            // every member key, one after the other
  std::unordered_map<std::string, int> by_pointer_;  // from_lines: pointer -> line
};

// Offsets of the first character of every line: line_starts[k] starts line k + 1.
std::vector<std::size_t> line_starts_of(const std::string& text);
// 1-based line of a byte offset.
int line_at_offset(const std::vector<std::size_t>& line_starts, std::size_t offset);

}  // namespace orch
