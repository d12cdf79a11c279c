#include "batch/template_binder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <set>

#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "json/json_text.hpp"

namespace orch::batch {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// One piece of a string: literal text, or a placeholder key.
struct Piece {
  bool placeholder = false;
  std::string text;
};

bool valid_key(const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size() || key.find('.', dot + 1) != std::string::npos)
    return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

// Splits a string into literal text and placeholders; returns an error message or "".
std::string split(const std::string& s, std::vector<Piece>& pieces) {
  std::string literal;
  for (std::size_t i = 0; i < s.size();) {
    if (s.compare(i, 3, "$${") == 0) {
      literal += "${";
      i += 3;
    } else if (s.compare(i, 2, "${") == 0) {
      const auto close = s.find('}', i + 2);
      if (close == std::string::npos) return fmt::format("unclosed placeholder \"{}\"", s.substr(i));
      const std::string key = s.substr(i + 2, close - i - 2);
      if (!valid_key(key))
        return fmt::format("malformed placeholder \"${{{}}}\": write ${{group.name}} (\"$${{\" for a literal \"${{\")", key);
      if (!literal.empty()) pieces.push_back({false, std::move(literal)});
      literal.clear();
      pieces.push_back({true, key});
      i = close + 1;
    } else {
      literal += s[i++];
    }
  }
  if (!literal.empty()) pieces.push_back({false, std::move(literal)});
  return {};
}

// The reference tokens from the root to the value being visited; its JSON pointer is made
// only where a message or a placeholder needs it (not for every value).
using PathTokens = std::vector<std::string>;
std::string pointer_of(const PathTokens& path) {
  std::string pointer;
  for (const auto& token : path) pointer = json_pointer_child(pointer, token);
  return pointer;
}

template <typename Json, typename Visit>
void walk_strings(Json& value, PathTokens& path, const Visit& visit) {
  if (value.is_string()) {
    visit(value, path);
  } else if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it) {
      path.push_back(it.key());
      walk_strings(it.value(), path, visit);
      path.pop_back();
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      path.push_back(std::to_string(i));
      walk_strings(value[i], path, visit);
      path.pop_back();
    }
  }
}

std::string as_text(const json& v) { return v.is_string() ? v.get<std::string>() : json_text(v); }

}  // namespace

std::map<std::string, json> flatten_values(const json& grouped) {
  std::map<std::string, json> out;
  for (auto g = grouped.begin(); g != grouped.end(); ++g)
    if (g->is_object())
      for (auto p = g->begin(); p != g->end(); ++p) out[g.key() + "." + p.key()] = *p;
  return out;
}

std::vector<Placeholder> find_placeholders(const JsonDocument& tmpl, Diagnostics& diags) {
  std::vector<Placeholder> found;
  PathTokens path;
  walk_strings(tmpl.root(), path, [&](const json& s, const PathTokens& at) {
    std::vector<Piece> pieces;
    const std::string problem = split(s.get<std::string>(), pieces);
    if (!problem.empty()) {
      diags.error(tmpl.where(pointer_of(at)), problem);
      return;
    }
    for (const auto& p : pieces)
      if (p.placeholder) found.push_back({p.text, pointer_of(at), pieces.size() == 1});
  });
  return found;
}

Diagnostics check_template(const LogicalScenario& logical, const JsonDocument& tmpl) {
  return check_template(logical, std::vector<const JsonDocument*>{&tmpl});
}

Diagnostics check_template(const LogicalScenario& logical, const std::vector<const JsonDocument*>& docs) {
  Diagnostics diags;
  const auto keys = logical.keys();
  std::set<std::string> used;
  std::string names;
  for (const JsonDocument* tmpl : docs) {
    names += (names.empty() ? "" : " and ") + tmpl->path();
    for (const auto& p : find_placeholders(*tmpl, diags)) {
      used.insert(p.key);
      if (!logical.find(p.key))
        diags.error(tmpl->where(p.pointer), fmt::format("placeholder ${{{}}} names no parameter of logical scenario {}{}",
                                                        p.key, logical.file.string(), did_you_mean(p.key, keys)));
    }
  }
  for (const auto& spec : logical.parameters)
    if (!used.count(spec.key()))
      diags.error(spec.where, fmt::format("parameter \"{}\" is used nowhere in the template {}: bind it with "
                                          "\"${{{}}}\" or remove it", spec.key(), names, spec.key()));
  return diags;
}

ordered_json bind_template(const JsonDocument& tmpl, const std::map<std::string, json>& values) {
  // The tree is parsed again in document order, so the bound file reads like the template
  // (a tree read from YAML has no JSON text: its keys come sorted).
  ordered_json out = tmpl.text().empty() ? ordered_json(tmpl.root()) : ordered_json::parse(tmpl.text());
  Diagnostics diags;
  std::vector<std::string> names;
  for (const auto& [k, v] : values) names.push_back(k);
  PathTokens path;
  walk_strings(out, path, [&](ordered_json& s, const PathTokens& at) {
    std::vector<Piece> pieces;
    const std::string problem = split(s.get<std::string>(), pieces);
    if (!problem.empty()) {
      diags.error(tmpl.where(pointer_of(at)), problem);
      return;
    }
    std::string text;
    for (const auto& p : pieces) {
      if (!p.placeholder) {
        text += p.text;
        continue;
      }
      const auto it = values.find(p.text);
      if (it == values.end()) {
        diags.error(tmpl.where(pointer_of(at)),
                    fmt::format("placeholder ${{{}}} has no value{}", p.text, did_you_mean(p.text, names)));
        return;
      }
      if (pieces.size() == 1) {
        s = ordered_json(it->second);  // keeps the value's JSON type
        return;
      }
      text += as_text(it->second);
    }
    s = text;
  });
  if (diags.has_errors()) throw ScenarioError(diags);
  return out;
}

}  // namespace orch::batch
