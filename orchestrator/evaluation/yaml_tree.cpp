#include "evaluation/yaml_tree.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/errors.hpp"
#include "core/utf8.hpp"

namespace orch {

namespace {

using Lines = std::unordered_map<std::string, int>;

nlohmann::json scalar(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  if (node.Tag() == "!") return text;  // quoted: a string whatever it looks like
  static const std::regex null_re("~|null|Null|NULL|");
  static const std::regex true_re("true|True|TRUE");
  static const std::regex false_re("false|False|FALSE");
  static const std::regex int_re("[-+]?[0-9]+");
  static const std::regex float_re(R"([-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?)");
  if (std::regex_match(text, null_re)) return nullptr;
  if (std::regex_match(text, true_re)) return true;
  if (std::regex_match(text, false_re)) return false;
  if (std::regex_match(text, int_re)) {
    long long v = 0;
    const auto [end, ec] = std::from_chars(text.data() + (text[0] == '+'), text.data() + text.size(), v);
    if (ec == std::errc() && end == text.data() + text.size()) return v;
  }
  if (std::regex_match(text, float_re)) return std::stod(text);
  return text;
}

nlohmann::json convert(const YAML::Node& node, const std::string& pointer, const std::string& path, Lines& lines) {
  lines[pointer] = node.Mark().line + 1;
  switch (node.Type()) {
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined: return nullptr;
    case YAML::NodeType::Scalar: return scalar(node);
    case YAML::NodeType::Sequence: {
      nlohmann::json out = nlohmann::json::array();
      std::size_t i = 0;
      for (const auto& item : node) {
        out.push_back(convert(item, json_pointer_child(pointer, i), path, lines));
        ++i;
      }
      return out;
    }
    case YAML::NodeType::Map: {
      nlohmann::json out = nlohmann::json::object();
      for (const auto& kv : node) {
        const std::string child_pointer = json_pointer_child(pointer, kv.first.Scalar());
        if (!kv.first.IsScalar())
          throw ScenarioError(SourceLocation{path, pointer, kv.first.Mark().line + 1}, "a key must be a plain name");
        const std::string& key = kv.first.Scalar();
        if (out.contains(key))
          throw ScenarioError(SourceLocation{path, child_pointer, kv.first.Mark().line + 1},
                              "duplicate key: the same key appears twice in one mapping");
        out[key] = convert(kv.second, child_pointer, path, lines);
        lines[child_pointer] = kv.first.Mark().line + 1;  // the key's line, as for JSON
      }
      return out;
    }
  }
  return nullptr;
}

}  // namespace

JsonDocument parse_yaml_document(const std::string& text, const std::string& path_for_messages) {
  // YAML is Unicode text; yaml-cpp passes any bytes through, and an ill-formed string would
  // reach the outputs (found by the soak, seed 2679876088: an internal error). The first
  // line that is not UTF-8 is named.
  if (!is_valid_utf8(text)) {
    int line = 1;
    for (std::size_t start = 0; start < text.size(); ++line) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      if (!is_valid_utf8(std::string_view(text).substr(start, end - start))) break;
      start = end + 1;
    }
    throw ScenarioError(SourceLocation{path_for_messages, "", line}, "invalid UTF-8: a YAML file is UTF-8 text");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(SourceLocation{path_for_messages, "", e.mark.line + 1}, "invalid YAML: " + e.msg);
  }
  Lines lines;
  nlohmann::json tree = convert(root, "", path_for_messages, lines);
  return JsonDocument::from_tree(std::move(tree), path_for_messages, std::move(lines));
}

JsonDocument load_yaml_document(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(SourceLocation{path, "", 0}, "cannot open file for reading");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_yaml_document(buf.str(), path);
}

}  // namespace orch
