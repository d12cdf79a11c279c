#include "json/json_document.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/errors.hpp"
#include "core/files.hpp"
#include "core/utf8.hpp"
#include "json/json_scan.hpp"

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

// A SAX handler that accepts every event and stops at the first error; passes override
// what they look at.
struct PassingSax : nlohmann::json_sax<nlohmann::json> {
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }
};

// The cheap pass every document gets: does any object repeat a key? (Which one, and on
// which line, the LineIndex pass finds when the answer is yes.) Keys are compared when
// their object ends; the key lists of each depth are kept for reuse. A second pass over the
// text, yet faster than one: the same check inside nlohmann's parse callback made the ALKS
// waypoint file's load 50 % slower (0.145 s against 0.094 s before the first step).
class DuplicateKeyCheck : public PassingSax {
 public:
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

 private:
  std::vector<std::vector<std::string>> keys_;
  std::size_t depth_ = 0;
};

// Before anything recursive sees the text: a depth far above any real file (scenarios nest
// about 8 deep) stops the parse with the line where it is exceeded. One pass over the bytes,
// skipping strings.
void check_nesting_depth(const std::string& text, const std::string& path) {
  std::size_t depth = 0;
  for_each_outside_strings(text, [&](std::size_t i, char c) {
    if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw ScenarioError(SourceLocation{path, "", line_at_offset(line_starts_of(text), i)},
                            fmt::format("values nested more than {} deep (arrays and objects inside each other)",
                                        kMaxJsonDepth));
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  });
}

// Where a parse stops: the SAX parser reports every error with its byte position.
std::size_t error_offset(const std::string& text) {
  struct Locator : PassingSax {
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception&) override {
      offset = position > 0 ? position - 1 : 0;
      return false;
    }
    std::size_t offset = 0;
  } locator;
  nlohmann::json::sax_parse(text, &locator);
  return locator.offset;
}

// nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3,
// column 5: syntax error ..."; keep only what follows the position.
std::string syntax_message(const std::string& what) {
  auto colon = what.find(": ", what.find("column"));
  // nlohmann quotes the bytes it last read, which may be the ill-formed UTF-8 it rejects.
  return valid_utf8(colon == std::string::npos ? what : what.substr(colon + 2));
}

}  // namespace

void release_tree(nlohmann::json& value) noexcept {
  if (value.is_array()) {
    auto& items = value.get_ref<nlohmann::json::array_t&>();
    for (auto& item : items)
      if (item.is_structured()) release_tree(item);
    items.clear();  // scalars only now: each is freed where it is
  } else if (value.is_object()) {
    auto& members = value.get_ref<nlohmann::json::object_t&>();
    for (auto& [key, member] : members)
      if (member.is_structured()) release_tree(member);
    members.clear();
  }
}

JsonDocument::~JsonDocument() { release_tree(root_); }

JsonDocument JsonDocument::load(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw ScenarioError(SourceLocation{path, "", 0}, "is a folder, not a JSON file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(SourceLocation{path, "", 0}, fmt::format("cannot open file for reading ({})", std::strerror(errno)));
  // One byte more than the limit, so that parse() names a file that is too large.
  std::string text = read_open_file(in, path, kMaxJsonBytes + 1);
  if (in.bad()) throw ScenarioError(SourceLocation{path, "", 0}, "cannot read the file");
  return parse(std::move(text), path);
}

JsonDocument JsonDocument::parse(std::string text, const std::string& path_for_messages) {
  JsonDocument doc;
  doc.path_ = path_for_messages;
  doc.text_ = std::move(text);
  if (doc.text_.size() > kMaxJsonBytes)
    throw ScenarioError(SourceLocation{doc.path_, "", 0},
                        fmt::format("the file is {} bytes; JSON files of more than {} bytes are not read", doc.text_.size(),
                                    kMaxJsonBytes));
  check_nesting_depth(doc.text_, doc.path_);
  try {
    doc.root_ = nlohmann::json::parse(doc.text_);
  } catch (const nlohmann::json::parse_error& e) {
    const std::size_t byte = e.byte > 0 ? e.byte - 1 : 0;
    throw ScenarioError(SourceLocation{doc.path_, "", line_at_offset(line_starts_of(doc.text_), byte)},
                        "invalid JSON: " + syntax_message(e.what()));
  } catch (const nlohmann::json::exception& e) {
    // A number beyond double's range (1e400) is out_of_range 406, which carries no position.
    throw ScenarioError(SourceLocation{doc.path_, "", line_at_offset(line_starts_of(doc.text_), error_offset(doc.text_))},
                        "invalid JSON: " + valid_utf8(e.what()));
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
  doc.lines_ = std::make_shared<const LineIndex>(LineIndex::from_lines(std::move(lines)));
  return doc;
}

// The line of every value, recorded on the first question (most documents are never
// asked: a waypoint file of 57,000 points would spend most of its load time here).
const LineIndex& JsonDocument::lines() const {
  if (!lines_) lines_ = std::make_shared<const LineIndex>(LineIndex::build(text_, path_));
  return *lines_;
}

int JsonDocument::line_of(const std::string& pointer) const { return lines().line_of(pointer); }

}  // namespace orch
