#include "json/line_index.hpp"

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>
#include <unordered_set>

#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/json_scan.hpp"

namespace orch {

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

// RFC 6901: "~1" is '/', "~0" is '~'.
std::string unescape_token(std::string_view token) {
  std::string out;
  out.reserve(token.size());
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (token[i] == '~' && i + 1 < token.size() && (token[i + 1] == '0' || token[i + 1] == '1')) {
      out += token[i + 1] == '0' ? '~' : '/';
      ++i;
    } else {
      out += token[i];
    }
  }
  return out;
}

// An array index token: digits only, no leading zero (RFC 6901).
bool array_index(std::string_view token, std::size_t& index) {
  if (token.empty() || token.size() > 10 || (token.size() > 1 && token[0] == '0')) return false;
  index = 0;
  for (char c : token) {
    if (c < '0' || c > '9') return false;
    index = index * 10 + static_cast<std::size_t>(c - '0');
  }
  return true;
}

// At most this many values in a text nlohmann parses: every value but the root follows a
// '[', a '{' or a ',' outside strings. Reserving it up front means the entries are never
// copied into a larger vector while the index grows (for a moment three times the index's
// size, with a 100 MB file; docs/hardening.md).
std::size_t value_bound(const std::string& text) {
  std::size_t bound = 1;
  for_each_outside_strings(text, [&](std::size_t, char c) {
    if (c == ',' || c == '[' || c == '{') ++bound;
  });
  return bound;
}

}  // namespace

class LineIndexBuilder : public nlohmann::json_sax<nlohmann::json> {
 public:
  LineIndexBuilder(LineIndex& index, const std::size_t& last, const std::vector<std::size_t>& line_starts)
      : index_(index), last_(last), line_starts_(line_starts) {}

  bool null() override { return scalar(); }
  bool boolean(bool) override { return scalar(); }
  bool number_integer(number_integer_t) override { return scalar(); }
  bool number_unsigned(number_unsigned_t) override { return scalar(); }
  bool number_float(number_float_t, const string_t&) override { return scalar(); }
  bool string(string_t&) override { return scalar(); }
  bool binary(binary_t&) override { return scalar(); }
  bool start_object(std::size_t) override { return open(LineIndex::Kind::Object); }
  bool start_array(std::size_t) override { return open(LineIndex::Kind::Array); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    Frame& top = stack_.back();
    if (!top.keys.insert(k).second) {
      duplicate_pointer_ = json_pointer_child(open_pointer(), k);
      duplicate_line_ = current_line();
      return false;  // stops the parse; reported by build()
    }
    pending_key_offset_ = static_cast<std::uint32_t>(index_.keys_.size());
    pending_key_size_ = static_cast<std::uint32_t>(k.size());
    index_.keys_ += k;
    pending_line_ = current_line();  // a member is located at its key
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

  std::string duplicate_pointer_;
  int duplicate_line_ = 0;

 private:
  struct Frame {
    std::uint32_t entry;
    std::uint32_t children = 0;
    std::unordered_set<std::string> keys;  // objects only: finds a repeated key
  };

  int current_line() const { return line_at_offset(line_starts_, last_); }

  std::uint32_t add(LineIndex::Kind kind) {
    LineIndex::Entry e;
    e.kind = kind;
    const bool member = !stack_.empty() && index_.entries_[stack_.back().entry].kind == LineIndex::Kind::Object;
    e.line = member ? pending_line_ : current_line();
    if (member) {
      e.key_offset = pending_key_offset_;
      e.key_size = pending_key_size_;
    }
    if (!stack_.empty()) ++stack_.back().children;
    index_.entries_.push_back(e);
    return static_cast<std::uint32_t>(index_.entries_.size() - 1);
  }
  bool scalar() {
    const auto i = add(LineIndex::Kind::Scalar);
    index_.entries_[i].end = i + 1;
    return true;
  }
  bool open(LineIndex::Kind kind) {
    stack_.push_back(Frame{add(kind), 0, {}});
    return true;
  }
  bool close() {
    index_.entries_[stack_.back().entry].end = static_cast<std::uint32_t>(index_.entries_.size());
    stack_.pop_back();
    return true;
  }
  // Pointer of the innermost open value, made only for a message.
  std::string open_pointer() const {
    std::string pointer;
    for (std::size_t d = 1; d < stack_.size(); ++d) {
      const Frame& parent = stack_[d - 1];
      if (index_.entries_[parent.entry].kind == LineIndex::Kind::Array)
        pointer = json_pointer_child(pointer, static_cast<std::size_t>(parent.children - 1));
      else
        pointer = json_pointer_child(pointer, std::string(index_.key_of(index_.entries_[stack_[d].entry])));
    }
    return pointer;
  }

  LineIndex& index_;
  const std::size_t& last_;
  const std::vector<std::size_t>& line_starts_;
  std::vector<Frame> stack_;
  std::uint32_t pending_key_offset_ = 0;
  std::uint32_t pending_key_size_ = 0;
  int pending_line_ = 0;
};

LineIndex LineIndex::build(const std::string& text, const std::string& path_for_messages) {
  LineIndex index;
  index.entries_.reserve(value_bound(text));
  const std::vector<std::size_t> line_starts = line_starts_of(text);
  std::size_t last = 0;
  LineIndexBuilder builder(index, last, line_starts);
  const char* b = text.data();
  TrackingIterator first{b, b, &last};
  TrackingIterator end{b + text.size(), b, &last};
  const bool complete = nlohmann::json::sax_parse(first, end, &builder);
  if (!complete && !builder.duplicate_pointer_.empty()) {
    throw ScenarioError(SourceLocation{path_for_messages, builder.duplicate_pointer_, builder.duplicate_line_},
                        "duplicate key: the same key appears twice in one object");
  }
  return index;
}

LineIndex LineIndex::from_lines(std::unordered_map<std::string, int> lines) {
  LineIndex index;
  index.by_pointer_ = std::move(lines);
  return index;
}

int LineIndex::line_of(std::string_view pointer) const {
  if (!by_pointer_.empty()) {
    // The pointer, else its nearest ancestor that has a line.
    std::string p(pointer);
    while (true) {
      if (const auto it = by_pointer_.find(p); it != by_pointer_.end()) return it->second;
      if (p.empty()) return 0;
      const auto slash = p.rfind('/');
      p.erase(slash == std::string::npos ? 0 : slash);
    }
  }
  if (entries_.empty()) return 0;
  std::uint32_t at = 0;
  while (!pointer.empty() && pointer.front() == '/') {
    pointer.remove_prefix(1);
    const std::size_t slash = pointer.find('/');
    const std::string token = unescape_token(pointer.substr(0, slash));
    pointer = slash == std::string_view::npos ? std::string_view{} : pointer.substr(slash);
    const Entry& node = entries_[at];
    std::size_t wanted = 0;
    if (node.kind == Kind::Scalar || (node.kind == Kind::Array && !array_index(token, wanted))) break;
    std::uint32_t found = node.end;
    std::size_t position = 0;
    // Children follow their parent; each child's `end` is where its next sibling starts.
    for (std::uint32_t child = at + 1; child < node.end; child = entries_[child].end, ++position) {
      if (node.kind == Kind::Array ? position == wanted : key_of(entries_[child]) == token) {
        found = child;
        break;
      }
    }
    if (found == node.end) break;
    at = found;
  }
  return entries_[at].line;
}

}  // namespace orch
