#include "openscenario/element_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/plausible.hpp"
#include "core/suggest.hpp"
#include "openscenario/expression.hpp"
#include "openscenario/standard_elements.hpp"
#include "openscenario/text_number.hpp"

namespace orch::openscenario {

std::optional<std::string> Element::raw(const char* attribute) {
  attributes_asked_.insert(attribute);
  const pugi::xml_attribute a = node_.attribute(attribute);
  if (!a) return std::nullopt;
  try {
    return substitute(a.value(), *scope_);
  } catch (const ExpressionError& e) {
    fail_attribute(attribute, e.what());
  }
}

std::optional<std::string> Element::optional_text(const char* attribute) { return raw(attribute); }

std::string Element::text(const char* attribute) {
  auto value = raw(attribute);
  if (!value) missing_attribute(attribute);
  return *value;
}

void Element::missing_attribute(const char* attribute) const {
  // A present attribute that is a near miss of the missing one explains it best.
  for (const pugi::xml_attribute a : node_.attributes())
    if (!attributes_asked_.contains(a.name()) && !closest_match(a.name(), {attribute}).empty())
      fail_attribute(a.name(), fmt::format("unknown attribute {} of {}{}", a.name(), name(),
                                           did_you_mean(a.name(), {attribute})));
  fail_attribute(attribute, "missing attribute");
}

namespace {
// Attributes that are a coordinate or a length wherever the standard uses them (positions,
// distances, offsets): a magnitude no map can hold is refused (core/plausible.hpp). Names
// that mean different quantities in different elements ("value") are left to their readers.
std::optional<Quantity> quantity_of(std::string_view attribute) {
  static constexpr std::string_view coordinates[] = {"x", "y", "z"};
  static constexpr std::string_view lengths[] = {"s", "t", "ds", "dsLane", "dx", "dy", "dz", "offset", "distance"};
  if (std::find(std::begin(coordinates), std::end(coordinates), attribute) != std::end(coordinates))
    return Quantity::Coordinate;
  if (std::find(std::begin(lengths), std::end(lengths), attribute) != std::end(lengths)) return Quantity::Length;
  return std::nullopt;
}
}  // namespace

std::optional<double> Element::optional_number(const char* attribute) {
  const auto value = raw(attribute);
  if (!value) return std::nullopt;
  const auto d = parse_whole<double>(*value);
  if (!d) fail_attribute(attribute, fmt::format("expected a number, found \"{}\"", *value));
  if (const auto quantity = quantity_of(attribute))
    if (const auto why = implausible(*d, *quantity)) fail_attribute(attribute, fmt::format("{} {}", attribute, *why));
  return d;
}

double Element::number(const char* attribute) {
  const auto value = optional_number(attribute);
  if (!value) missing_attribute(attribute);
  return *value;
}

std::optional<int> Element::optional_integer(const char* attribute) {
  const auto value = raw(attribute);
  if (!value) return std::nullopt;
  // "-4" and, from an expression, "-4" again (format_number writes integers bare).
  const auto n = parse_whole<int>(*value);
  if (!n) fail_attribute(attribute, fmt::format("expected a whole number, found \"{}\"", *value));
  return n;
}

int Element::integer(const char* attribute) {
  const auto value = optional_integer(attribute);
  if (!value) missing_attribute(attribute);
  return *value;
}

std::optional<bool> Element::optional_boolean(const char* attribute) {
  const auto value = raw(attribute);
  if (!value) return std::nullopt;
  if (*value == "true" || *value == "1") return true;
  if (*value == "false" || *value == "0") return false;
  fail_attribute(attribute, fmt::format("expected true or false, found \"{}\"", *value));
}

bool Element::boolean(const char* attribute) {
  const auto value = optional_boolean(attribute);
  if (!value) missing_attribute(attribute);
  return *value;
}

std::string Element::choice_text(const char* attribute, const std::vector<std::string>& words) {
  const std::string value = text(attribute);
  for (const auto& w : words)
    if (w == value) return value;
  fail_attribute(attribute, fmt::format("expected one of {}, found \"{}\"{}", quoted_list(words), value,
                                        did_you_mean(value, words)));
}

void Element::ignore_attributes(const std::vector<std::string>& names) {
  attributes_asked_.insert(names.begin(), names.end());
}

std::vector<Element> Element::children(const char* name) {
  children_asked_.insert(name);
  std::vector<Element> out;
  for (const pugi::xml_node c : node_.children(name)) out.emplace_back(*source_, c, *scope_);
  return out;
}

std::optional<Element> Element::optional_child(const char* name) {
  auto all = children(name);
  if (all.empty()) return std::nullopt;
  if (all.size() > 1) all[1].fail(fmt::format("{} may appear only once here", name));
  return all.front();
}

Element Element::child(const char* element) {
  auto c = optional_child(element);
  if (!c) {
    for (const pugi::xml_node n : node_.children())
      if (n.type() == pugi::node_element && !children_asked_.contains(n.name()) &&
          !closest_match(n.name(), {element}).empty())
        Element(*source_, n, *scope_).fail(
            fmt::format("unknown element {} in {}{}", n.name(), name(), did_you_mean(n.name(), {element})));
    fail(fmt::format("missing element {}", element));
  }
  return *c;
}

Element Element::one_of(const std::vector<std::string>& names) {
  children_asked_.insert(names.begin(), names.end());
  std::optional<Element> found;
  for (const pugi::xml_node c : node_.children()) {
    if (c.type() != pugi::node_element) continue;
    if (std::find(names.begin(), names.end(), c.name()) == names.end()) continue;
    if (found) Element(*source_, c, *scope_).fail(fmt::format("{} holds exactly one of {}", name(), quoted_list(names)));
    found.emplace(*source_, c, *scope_);
  }
  if (found) return *found;
  finish();  // an unknown child explains the missing choice best
  fail(fmt::format("expected one of the elements {}", quoted_list(names)));
}

void Element::ignore_children(const std::vector<std::string>& names) {
  children_asked_.insert(names.begin(), names.end());
}

namespace {
bool is_xml_attribute(std::string_view name) {
  return name == "xmlns" || name.starts_with("xmlns:") || name.starts_with("xsi:");
}
}  // namespace

void Element::finish() {
  const std::vector<std::string> known_attributes(attributes_asked_.begin(), attributes_asked_.end());
  for (const pugi::xml_attribute a : node_.attributes()) {
    if (attributes_asked_.contains(a.name()) || is_xml_attribute(a.name())) continue;
    fail_attribute(a.name(), fmt::format("unknown attribute {} of {}{}", a.name(), name(),
                                         did_you_mean(a.name(), known_attributes)));
  }
  const std::vector<std::string> known_children(children_asked_.begin(), children_asked_.end());
  for (const pugi::xml_node c : node_.children()) {
    if (c.type() != pugi::node_element || children_asked_.contains(c.name())) continue;
    const Element child(*source_, c, *scope_);
    // An element of the standard is never a misspelling, even when it is close to one read
    // here (RelativeClearanceCondition ~ RelativeDistanceCondition).
    if (is_standard_element(c.name()))
      child.fail(fmt::format("{} in {} is an OpenSCENARIO element the orchestrator does not run there (not "
                             "supported, or not one the schema allows in {})",
                             c.name(), name(), name()));
    child.fail(fmt::format("unknown element {} in {}{}", c.name(), name(), did_you_mean(c.name(), known_children)));
  }
}

void Element::fail(const std::string& message) const { source_->fail(node_, message); }

void Element::fail_attribute(const char* attribute, const std::string& message) const {
  throw ScenarioError(source_->where(node_, attribute), message);
}

}  // namespace orch::openscenario
