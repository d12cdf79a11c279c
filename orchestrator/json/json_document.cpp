#include "json/json_document.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <vector>

#include "core/errors.hpp"

namespace orch {

std::string json_pointer_child(const std::string& parent, const std::string& key) {
  std::string escaped;
  for (char c : key) {
    if (c == '~') escaped += "~0";
    else if (c == '/') escaped += "~1";
    else escaped += c;
  }
  return parent + "/" + escaped;
}

std::string json_pointer_child(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

namespace {

// Iterator over the text that remembers the offset of the last non-blank character the
// parser consumed. The lexer reads one character past a number; skipping blanks keeps a
// number at the end of a line on its own line.
struct TrackingIterator {
  using iterator_category = std::forward_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* p = nullptr;
  const char* begin = nullptr;
  std::size_t* last_significant = nullptr;

  reference operator*() const { return *p; }
  TrackingIterator& operator++() {
    const char c = *p;
    if (c != ' ' && c != '\n' && c != '\r' && c != '\t')
      *last_significant = static_cast<std::size_t>(p - begin);
    ++p;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const TrackingIterator& o) const { return p == o.p; }
  bool operator!=(const TrackingIterator& o) const { return p != o.p; }
};

class LineRecorder : public nlohmann::json_sax<nlohmann::json> {
 public:
  LineRecorder(const std::size_t& last, const std::vector<std::size_t>& line_starts,
               std::unordered_map<std::string, int>& lines)
      : last_(last), line_starts_(line_starts), lines_(lines) {}

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    const std::string ptr = next_pointer();
    stack_.push_back({ptr, false, 0, {}, {}});
    return true;
  }
  bool key(string_t& k) override {
    Frame& top = stack_.back();
    if (!top.keys.insert(k).second) {
      duplicate_ = json_pointer_child(top.pointer, k);
      duplicate_line_ = current_line();
      return false;  // stops the parse; reported by the caller
    }
    top.pending = json_pointer_child(top.pointer, k);
    lines_[top.pending] = current_line();
    return true;
  }
  bool end_object() override {
    stack_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    const std::string ptr = next_pointer();
    stack_.push_back({ptr, true, 0, {}, {}});
    return true;
  }
  bool end_array() override {
    stack_.pop_back();
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

  std::string duplicate_;
  int duplicate_line_ = 0;

 private:
  struct Frame {
    std::string pointer;
    bool is_array;
    std::size_t index;
    std::string pending;
    std::set<std::string> keys;
  };

  int current_line() const {
    auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), last_);
    return static_cast<int>(it - line_starts_.begin());
  }
  // Pointer of the value that starts now; records its line.
  std::string next_pointer() {
    if (stack_.empty()) {
      lines_[""] = current_line();
      return "";
    }
    Frame& top = stack_.back();
    if (!top.is_array) return top.pending;  // recorded at its key
    std::string ptr = json_pointer_child(top.pointer, top.index++);
    lines_[ptr] = current_line();
    return ptr;
  }
  bool value() {
    next_pointer();
    return true;
  }

  const std::size_t& last_;
  const std::vector<std::size_t>& line_starts_;
  std::unordered_map<std::string, int>& lines_;
  std::vector<Frame> stack_;
};

// The cheap pass every document gets: does any object repeat a key? (Which one, and on
// which line, the LineRecorder pass finds when the answer is yes.) Keys are compared when
// their object ends; the key lists of each depth are kept for reuse. A second pass over the
// text, yet faster than one: the same check inside nlohmann's parse callback made the ALKS
// waypoint file's load 50 % slower (0.145 s against 0.094 s before the first step).
class DuplicateKeyCheck : public nlohmann::json_sax<nlohmann::json> {
 public:
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    if (depth_ == keys_.size()) keys_.emplace_back();
    keys_[depth_++].clear();
    return true;
  }
  bool key(string_t& k) override {
    keys_[depth_ - 1].push_back(k);
    return true;
  }
  bool end_object() override {
    auto& keys = keys_[--depth_];
    std::sort(keys.begin(), keys.end());
    return std::adjacent_find(keys.begin(), keys.end()) == keys.end();  // false stops the parse
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

 private:
  std::vector<std::vector<std::string>> keys_;
  std::size_t depth_ = 0;
};

std::vector<std::size_t> line_starts_of(const std::string& text) {
  std::vector<std::size_t> line_starts{0};
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') line_starts.push_back(i + 1);
  return line_starts;
}

int line_at_offset(const std::vector<std::size_t>& line_starts, std::size_t offset) {
  auto it = std::upper_bound(line_starts.begin(), line_starts.end(), offset);
  return static_cast<int>(it - line_starts.begin());
}

// nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3,
// column 5: syntax error ..."; keep only what follows the position.
std::string syntax_message(const std::string& what) {
  auto colon = what.find(": ", what.find("column"));
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

JsonDocument JsonDocument::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(SourceLocation{path, "", 0}, "cannot open file for reading");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse(buf.str(), path);
}

JsonDocument JsonDocument::parse(std::string text, const std::string& path_for_messages) {
  JsonDocument doc;
  doc.path_ = path_for_messages;
  doc.text_ = std::move(text);
  try {
    doc.root_ = nlohmann::json::parse(doc.text_);
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t byte = e.byte > 0 ? e.byte - 1 : 0;
    throw ScenarioError(SourceLocation{doc.path_, "", line_at_offset(line_starts_of(doc.text_), byte)},
                        "invalid JSON: " + syntax_message(e.what()));
  }
  DuplicateKeyCheck check;
  if (!nlohmann::json::sax_parse(doc.text_, &check)) {
    (void)doc.lines();  // throws, naming the repeated key and its line
    throw ScenarioError(SourceLocation{doc.path_, "", 0}, "duplicate key: the same key appears twice in one object");
  }
  return doc;
}

JsonDocument JsonDocument::from_tree(nlohmann::json root, const std::string& path,
                                     std::unordered_map<std::string, int> lines) {
  JsonDocument doc;
  doc.path_ = path;
  doc.root_ = std::move(root);
  doc.lines_ = std::make_shared<const std::unordered_map<std::string, int>>(std::move(lines));
  return doc;
}

// The line of every value, recorded on the first question (most documents are never
// asked: a waypoint file of 57,000 points would spend most of its load time here).
const std::unordered_map<std::string, int>& JsonDocument::lines() const {
  if (lines_) return *lines_;
  auto lines = std::make_shared<std::unordered_map<std::string, int>>();
  const std::vector<std::size_t> line_starts = line_starts_of(text_);
  std::size_t last = 0;
  LineRecorder recorder(last, line_starts, *lines);
  const char* b = text_.data();
  TrackingIterator first{b, b, &last};
  TrackingIterator end{b + text_.size(), b, &last};
  const bool complete = nlohmann::json::sax_parse(first, end, &recorder);
  if (!complete && !recorder.duplicate_.empty()) {
    throw ScenarioError(SourceLocation{path_, recorder.duplicate_, recorder.duplicate_line_},
                        "duplicate key: the same key appears twice in one object");
  }
  lines_ = std::move(lines);
  return *lines_;
}

int JsonDocument::line_of(const std::string& pointer) const {
  const auto& lines = this->lines();
  std::string p = pointer;
  while (true) {
    auto it = lines.find(p);
    if (it != lines.end()) return it->second;
    if (p.empty()) return 0;
    p = p.substr(0, p.rfind('/'));
  }
}

}  // namespace orch
