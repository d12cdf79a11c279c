#include "xml/xml_source.hpp"

#include <algorithm>
#include <memory>

#include "core/files.hpp"

namespace orch::xml {

XmlSource XmlSource::load(const std::string& path) {
  std::string text;
  try {
    text = read_file(path);
  } catch (const OrchError& e) {
    throw ScenarioError(SourceLocation{path, "", 0}, e.what());
  }
  return parse(std::move(text), path);
}

XmlSource XmlSource::parse(std::string text, const std::string& name) {
  XmlSource source;
  source.file_ = name;
  source.text_ = std::move(text);
  source.line_starts_.push_back(0);
  for (std::size_t i = 0; i < source.text_.size(); ++i)
    if (source.text_[i] == '\n') source.line_starts_.push_back(i + 1);
  source.doc_ = std::make_unique<pugi::xml_document>();
  // Parse from our own buffer (pugixml skips a BOM) so offsets map back to lines.
  const pugi::xml_parse_result parsed = source.doc_->load_buffer(
      source.text_.data(), source.text_.size(), pugi::parse_default | pugi::parse_ws_pcdata_single,
      pugi::encoding_utf8);
  if (!parsed) {
    const auto offset = static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0));
    const auto line = std::upper_bound(source.line_starts_.begin(), source.line_starts_.end(), offset) -
                      source.line_starts_.begin();
    throw ScenarioError(SourceLocation{name, "", static_cast<int>(line)},
                        std::string("not well-formed XML: ") + parsed.description());
  }
  if (!source.doc_->document_element())
    throw ScenarioError(SourceLocation{name, "", 0}, "the file holds no XML element");
  return source;
}

int XmlSource::line_of(const pugi::xml_node& node) const {
  const std::ptrdiff_t offset = node.offset_debug();
  if (offset < 0) return 0;
  const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), static_cast<std::size_t>(offset));
  return static_cast<int>(it - line_starts_.begin());
}

std::string XmlSource::path_of(const pugi::xml_node& node) {
  std::vector<std::string> parts;
  for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) {
    std::string part = n.name();
    int index = 0;
    int same = 0;
    for (pugi::xml_node sibling = n.parent().first_child(); sibling; sibling = sibling.next_sibling()) {
      if (sibling.type() != pugi::node_element || std::string_view(sibling.name()) != n.name()) continue;
      ++same;
      if (sibling == n) index = same;
    }
    if (same > 1) part += "[" + std::to_string(index) + "]";
    parts.push_back(std::move(part));
  }
  std::string path;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) path += "/" + *it;
  return path;
}

SourceLocation XmlSource::where(const pugi::xml_node& node, std::string_view attribute) const {
  std::string path = path_of(node);
  if (!attribute.empty()) path += "/@" + std::string(attribute);
  return SourceLocation{file_, std::move(path), line_of(node)};
}

void XmlSource::fail(const pugi::xml_node& node, const std::string& message) const {
  throw ScenarioError(where(node), message);
}

}  // namespace orch::xml
