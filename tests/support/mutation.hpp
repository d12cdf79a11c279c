#pragma once
// Mutations of real input files for the property tests (tests/e2e/test_mutated_*_cli.cpp)
// and the soak (scripts/soak.sh): a value replaced, a key or attribute removed, an item
// duplicated, bytes overwritten, a number made extreme. Each is drawn from a seeded
// std::mt19937_64, so a seed and a run index name one mutant for good (on the same files).
//
// Seeds: the tests run a fixed list (kPropertySeeds below, every seed that ever failed
// included); ORCH_PROPERTY_SEED=N runs that one seed instead and ORCH_PROPERTY_RUNS=N
// changes the mutants per seed (the soak draws random seeds this way).
#include <pugixml.hpp>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace orch::test {

struct Mutation {
  std::string what;
  std::string text;
};

struct PropertySeeds {
  std::vector<std::uint64_t> seeds;
  int runs = 0;  // mutants per seed
};

// The fixed seeds of the README's test command: the same mutants on every run of it.
// 249426645: issue 22 (a wp_offset of 1e300, undefined behaviour in the grid projection);
// that mutant is also kept as a file (tests/data/regressions/).
inline PropertySeeds property_seeds(std::vector<std::uint64_t> fixed, int default_runs) {
  PropertySeeds p{std::move(fixed), default_runs};
  if (const char* s = std::getenv("ORCH_PROPERTY_SEED")) p.seeds = {std::stoull(s)};
  if (const char* r = std::getenv("ORCH_PROPERTY_RUNS")) p.runs = std::stoi(r);
  return p;
}

inline std::size_t pick(std::mt19937_64& rng, std::size_t n) {
  return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

// 1-4 bytes overwritten anywhere (strings included: invalid UTF-8).
inline Mutation overwrite_bytes(std::string text, std::mt19937_64& rng) {
  const std::size_t at = pick(rng, text.size());
  for (std::size_t i = 0, n = 1 + pick(rng, 4); i < n && at + i < text.size(); ++i)
    text[at + i] = static_cast<char>(pick(rng, 256));
  return {"bytes at offset " + std::to_string(at), std::move(text)};
}

// The factors that make a number extreme but keep it a number of the right type.
inline double extreme_factor(std::mt19937_64& rng) {
  static const double factors[] = {0.0, -1.0, 1e6, 1e-3};
  return factors[pick(rng, std::size(factors))];
}

// ---------------------------------------------------------------- JSON
inline void json_pointers(const nlohmann::ordered_json& v, const std::string& at, std::vector<std::string>& out) {
  out.push_back(at);
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) json_pointers(it.value(), at + "/" + it.key(), out);
  else if (v.is_array())
    for (std::size_t i = 0; i < v.size(); ++i) json_pointers(v[i], at + "/" + std::to_string(i), out);
}

inline Mutation mutate_json(const std::string& original, std::mt19937_64& rng) {
  using nlohmann::ordered_json;
  if (pick(rng, 10) == 0) return overwrite_bytes(original, rng);
  ordered_json doc = ordered_json::parse(original);
  std::vector<std::string> pointers;
  json_pointers(doc, "", pointers);
  const std::string p = pointers[1 + pick(rng, pointers.size() - 1)];
  ordered_json& v = doc[ordered_json::json_pointer(p)];
  std::string what;
  switch (pick(rng, 4)) {
    case 0: {  // a value of another type
      static const ordered_json others[] = {nullptr, true, -1, 1e300, "text", ordered_json::array(), ordered_json::object(),
                                            "NaN"};
      v = others[pick(rng, std::size(others))];
      what = "value replaced at " + p;
      break;
    }
    case 1: {  // a key removed (of the enclosing object)
      const auto slash = p.rfind('/');
      ordered_json& parent = doc[ordered_json::json_pointer(p.substr(0, slash))];
      if (parent.is_object()) parent.erase(p.substr(slash + 1));
      what = "key removed at " + p;
      break;
    }
    case 2: {  // a list item duplicated (the nearest enclosing list)
      std::string q = p;
      while (!q.empty() && !doc[ordered_json::json_pointer(q)].is_array()) q = q.substr(0, q.rfind('/'));
      ordered_json& list = doc[ordered_json::json_pointer(q)];
      if (list.is_array() && !list.empty()) list.push_back(list[pick(rng, list.size())]);
      what = "list item duplicated in " + q;
      break;
    }
    default: {  // extreme but valid: a number of the right type, reaching the engine
      std::vector<std::string> numbers;
      for (const auto& q : pointers)
        if (doc[ordered_json::json_pointer(q)].is_number()) numbers.push_back(q);
      if (numbers.empty()) return {"unchanged", original};
      const std::string q = numbers[pick(rng, numbers.size())];
      ordered_json& n = doc[ordered_json::json_pointer(q)];
      n = n.get<double>() * extreme_factor(rng);
      what = "number scaled at " + q;
    }
  }
  return {what, doc.dump(2)};
}

// ---------------------------------------------------------------- XML (.xosc, .xodr)
// Relative file references (LogicFile/SceneGraphFile filepath, catalog Directory path) made
// absolute against the original's folder, so that the mutant runs from a temporary folder.
inline void absolutize_paths(pugi::xml_node node, const std::filesystem::path& base) {
  for (pugi::xml_node child : node.children()) {
    for (pugi::xml_attribute a : child.attributes()) {
      const std::string name = a.name();
      const std::string value = a.value();
      // A parameter's value may be a file: <ParameterDeclaration name="Road" value="./road.xodr"/>.
      const bool file_value = name == "value" && std::string_view(child.name()) == "ParameterDeclaration" &&
                              (value.ends_with(".xodr") || value.ends_with(".xosc"));
      if (name != "filepath" && name != "path" && !file_value) continue;
      if (value.empty() || value[0] == '/' || value[0] == '$') continue;
      a.set_value((base / value).lexically_normal().string().c_str());
    }
    absolutize_paths(child, base);
  }
}

// The attribute that names the road network file (LogicFile's filepath, or the value of the
// parameter it refers to), or an empty attribute.
inline pugi::xml_attribute road_file_attribute(const pugi::xml_document& doc) {
  pugi::xml_attribute a = doc.select_node("//RoadNetwork/LogicFile").node().attribute("filepath");
  const std::string value = a.value();
  if (!value.starts_with("$")) return a;
  const std::string xpath = "//ParameterDeclaration[@name='" + value.substr(1) + "']";
  return doc.select_node(xpath.c_str()).node().attribute("value");
}

inline std::string xml_text(const pugi::xml_document& doc) {
  std::ostringstream out;
  doc.save(out, "  ");
  return out.str();
}

inline void xml_collect(pugi::xml_node node, std::vector<pugi::xml_node>& elements) {
  for (pugi::xml_node child : node.children())
    if (child.type() == pugi::node_element) {
      elements.push_back(child);
      xml_collect(child, elements);
    }
}

inline std::string xml_where(pugi::xml_node e, const char* attribute = nullptr) {
  std::string at = e.name();
  for (pugi::xml_node p = e.parent(); p && p.type() == pugi::node_element; p = p.parent()) at = std::string(p.name()) + "/" + at;
  return attribute ? at + "@" + attribute : at;
}

// `original` is already loaded into `doc` (paths made absolute); mutates it in place.
inline Mutation mutate_xml(pugi::xml_document& doc, std::mt19937_64& rng) {
  if (pick(rng, 10) == 0) return overwrite_bytes(xml_text(doc), rng);
  std::vector<pugi::xml_node> elements;
  xml_collect(doc, elements);
  std::vector<std::pair<pugi::xml_node, pugi::xml_attribute>> attributes;
  for (pugi::xml_node e : elements)
    for (pugi::xml_attribute a : e.attributes()) attributes.emplace_back(e, a);
  if (elements.size() < 2 || attributes.empty()) return {"unchanged", xml_text(doc)};
  std::string what;
  switch (pick(rng, 5)) {
    case 0: {  // an attribute's value replaced
      static const char* others[] = {"", "1e300", "-1e300", "inf", "nan", "-1", "0", "text", "9223372036854775808",
                                     "$undefinedParameter", "1e-300", "${1/0}"};
      auto [e, a] = attributes[pick(rng, attributes.size())];
      const char* v = others[pick(rng, std::size(others))];
      a.set_value(v);
      what = "attribute " + xml_where(e, a.name()) + " = \"" + v + "\"";
      break;
    }
    case 1: {  // an attribute removed
      auto [e, a] = attributes[pick(rng, attributes.size())];
      what = "attribute removed: " + xml_where(e, a.name());
      e.remove_attribute(a);
      break;
    }
    case 2: {  // an element duplicated
      pugi::xml_node e = elements[1 + pick(rng, elements.size() - 1)];
      what = "element duplicated: " + xml_where(e);
      e.parent().insert_copy_after(e, e);
      break;
    }
    case 3: {  // an element removed
      pugi::xml_node e = elements[1 + pick(rng, elements.size() - 1)];
      what = "element removed: " + xml_where(e);
      e.parent().remove_child(e);
      break;
    }
    default: {  // a number made extreme
      std::vector<std::pair<pugi::xml_node, pugi::xml_attribute>> numbers;
      for (const auto& [e, a] : attributes) {
        char* end = nullptr;
        std::strtod(a.value(), &end);
        if (end != a.value() && *end == '\0') numbers.emplace_back(e, a);
      }
      if (numbers.empty()) return {"unchanged", xml_text(doc)};
      auto [e, a] = numbers[pick(rng, numbers.size())];
      const double scaled = a.as_double() * extreme_factor(rng);
      std::ostringstream v;
      v.precision(17);
      v << scaled;
      a.set_value(v.str().c_str());
      what = "number scaled: " + xml_where(e, a.name()) + " = " + v.str();
    }
  }
  return {what, xml_text(doc)};
}

// ---------------------------------------------------------------- YAML (evaluation files)
// Line by line: evaluation files are small block-style YAML, one key per line.
inline Mutation mutate_yaml(const std::string& original, const std::filesystem::path& base, std::mt19937_64& rng) {
  std::vector<std::string> lines;
  std::istringstream in(original);
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find("Scenario: ");
    if (at != std::string::npos && line.find_first_not_of(' ') == at) {
      const std::string value = line.substr(at + 10);
      if (!value.empty() && value[0] != '/') line = line.substr(0, at + 10) + (base / value).lexically_normal().string();
    }
    lines.push_back(line);
  }
  const auto join = [&] {
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
  };
  if (pick(rng, 10) == 0) return overwrite_bytes(join(), rng);
  std::vector<std::size_t> keyed;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].find(": ") != std::string::npos && lines[i].find_first_not_of(' ') != std::string::npos &&
        lines[i][lines[i].find_first_not_of(' ')] != '#')
      keyed.push_back(i);
  if (keyed.empty()) return {"unchanged", join()};
  const std::size_t i = keyed[pick(rng, keyed.size())];
  const std::size_t colon = lines[i].find(": ");
  std::string what;
  switch (pick(rng, 4)) {
    case 0: {
      static const char* others[] = {"null", "true", "-1", "1e300", "-1e300", "text", "[]", "{}", ".nan", ".inf", "-.inf",
                                     "9223372036854775808"};
      const char* v = others[pick(rng, std::size(others))];
      lines[i] = lines[i].substr(0, colon + 2) + v;
      what = "line " + std::to_string(i + 1) + " value = " + v;
      break;
    }
    case 1:
      what = "line " + std::to_string(i + 1) + " removed";
      lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    case 2:
      what = "line " + std::to_string(i + 1) + " duplicated";
      lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
      break;
    default: {
      const std::string value = lines[i].substr(colon + 2);
      char* end = nullptr;
      const double d = std::strtod(value.c_str(), &end);
      if (end == value.c_str() || *end != '\0') return {"unchanged", join()};
      std::ostringstream v;
      v.precision(17);
      v << d * extreme_factor(rng);
      lines[i] = lines[i].substr(0, colon + 2) + v.str();
      what = "line " + std::to_string(i + 1) + " number scaled to " + v.str();
    }
  }
  return {what, join()};
}

}  // namespace orch::test
