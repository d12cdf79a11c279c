#pragma once
// An XML file loaded for reading user input (OpenSCENARIO, OpenDRIVE): keeps the text so
// every element can be named by file, line and element path in error messages.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "core/diagnostics.hpp"
#include "core/errors.hpp"

namespace orch::xml {

class XmlSource {
 public:
  // Reads and parses `path`; a UTF-8 byte order mark is accepted. Throws ScenarioError
  // naming the file and line when the file cannot be read or is not well-formed XML.
  static XmlSource load(const std::string& path);
  // Parses `text` as if it were the file `name` (tests, embedded documents).
  static XmlSource parse(std::string text, const std::string& name);

  XmlSource(XmlSource&&) = default;
  XmlSource& operator=(XmlSource&&) = default;

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] pugi::xml_node root() const { return doc_->document_element(); }
  // 1-based line of `node`'s start tag.
  [[nodiscard]] int line_of(const pugi::xml_node& node) const;
  // "/OpenSCENARIO/Storyboard/Story[2]/Act": the index only where siblings share the name.
  [[nodiscard]] static std::string path_of(const pugi::xml_node& node);
  [[nodiscard]] SourceLocation where(const pugi::xml_node& node, std::string_view attribute = {}) const;
  [[noreturn]] void fail(const pugi::xml_node& node, const std::string& message) const;

 private:
  XmlSource() = default;
  std::string file_;
  std::string text_;
  std::vector<std::size_t> line_starts_;
  std::unique_ptr<pugi::xml_document> doc_;
};

}  // namespace orch::xml
