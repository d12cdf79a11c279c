#pragma once
// Reads one OpenSCENARIO element: attribute values with parameters substituted and checked
// for type, child elements by name. finish() then reports every attribute and child element
// the reader did not ask for: a misspelt one with "did you mean", a standard element the
// orchestrator does not run as "not supported". Errors throw ScenarioError with file, line
// and element path.
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <pugixml.hpp>

#include "openscenario/model.hpp"
#include "openscenario/parameters.hpp"
#include "xml/xml_source.hpp"

namespace orch::openscenario {

class Element {
 public:
  Element(const xml::XmlSource& source, pugi::xml_node node, const ParameterScope& scope)
      : source_(&source), node_(node), scope_(&scope) {}

  [[nodiscard]] std::string_view name() const { return node_.name(); }
  [[nodiscard]] pugi::xml_node node() const { return node_; }
  [[nodiscard]] const xml::XmlSource& source() const { return *source_; }
  [[nodiscard]] const ParameterScope& scope() const { return *scope_; }
  [[nodiscard]] Place place() const { return {xml::XmlSource::path_of(node_), source_->line_of(node_)}; }
  [[nodiscard]] bool has(const char* attribute) const { return static_cast<bool>(node_.attribute(attribute)); }
  // This element read in another parameter scope (one its own ParameterDeclarations open:
  // Story, Maneuver, catalog entries); what was asked so far stays asked.
  [[nodiscard]] Element scoped(const ParameterScope& scope) const {
    Element e = *this;
    e.scope_ = &scope;
    return e;
  }

  // Attribute values, substituted. Optional ones return nullopt when absent.
  std::string text(const char* attribute);
  std::optional<std::string> optional_text(const char* attribute);
  double number(const char* attribute);
  std::optional<double> optional_number(const char* attribute);
  int integer(const char* attribute);
  std::optional<int> optional_integer(const char* attribute);
  bool boolean(const char* attribute);
  std::optional<bool> optional_boolean(const char* attribute);
  // One of a closed set of words; a near miss gets "did you mean".
  template <class T>
  T choice(const char* attribute, const std::vector<std::pair<std::string, T>>& choices);
  template <class T>
  std::optional<T> optional_choice(const char* attribute, const std::vector<std::pair<std::string, T>>& choices);
  // Attributes valid here that this reader does not use (descriptions, licenses, ...).
  void ignore_attributes(const std::vector<std::string>& names);

  std::optional<Element> optional_child(const char* name);
  Element child(const char* name);
  std::vector<Element> children(const char* name);
  // Exactly one child element, which must be one of `names` (an xsd:choice).
  Element one_of(const std::vector<std::string>& names);
  void ignore_children(const std::vector<std::string>& names);

  // Reports attributes and child elements present but not read. Call once after reading.
  // Namespace declarations and XML Schema instance attributes (xmlns, xmlns:xsi,
  // xsi:noNamespaceSchemaLocation, as the standard's own examples carry on the root) are
  // XML's, not OpenSCENARIO's, and allowed on any element.
  void finish();

  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_attribute(const char* attribute, const std::string& message) const;

 private:
  [[nodiscard]] std::optional<std::string> raw(const char* attribute);
  [[noreturn]] void missing_attribute(const char* attribute) const;
  [[nodiscard]] std::string choice_text(const char* attribute, const std::vector<std::string>& words);

  const xml::XmlSource* source_;
  pugi::xml_node node_;
  const ParameterScope* scope_;
  std::set<std::string, std::less<>> attributes_asked_;
  std::set<std::string, std::less<>> children_asked_;
};

template <class T>
T Element::choice(const char* attribute, const std::vector<std::pair<std::string, T>>& choices) {
  const auto value = optional_choice(attribute, choices);
  if (!value) missing_attribute(attribute);
  return *value;
}

template <class T>
std::optional<T> Element::optional_choice(const char* attribute, const std::vector<std::pair<std::string, T>>& choices) {
  std::vector<std::string> words;
  for (const auto& [word, value] : choices) words.push_back(word);
  if (!has(attribute)) {
    attributes_asked_.insert(attribute);
    return std::nullopt;
  }
  const std::string word = choice_text(attribute, words);
  for (const auto& [w, value] : choices)
    if (w == word) return value;
  return std::nullopt;  // unreachable: choice_text checked the word
}

}  // namespace orch::openscenario
