#include "openscenario/parameters.hpp"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "openscenario/date_time.hpp"
#include "openscenario/expression.hpp"
#include "openscenario/text_number.hpp"

namespace orch::openscenario {

const ParameterScope::Entry* ParameterScope::find(std::string_view name) const {
  for (const ParameterScope* s = this; s != nullptr; s = s->parent_) {
    const auto it = s->values_.find(name);
    if (it != s->values_.end()) return &it->second;
  }
  return nullptr;
}

std::optional<std::string> ParameterScope::value(std::string_view name) const {
  const Entry* e = find(name);
  return e != nullptr ? std::optional(e->value) : std::nullopt;
}

std::optional<std::string> ParameterScope::type(std::string_view name) const {
  const Entry* e = find(name);
  return e != nullptr ? std::optional(e->type) : std::nullopt;
}

std::optional<std::string> ParameterScope::key(std::string_view name) const {
  const Entry* e = find(name);
  return e != nullptr ? std::optional(e->key) : std::nullopt;
}

std::optional<std::string> parameter_type(std::string_view word) {
  if (word == "int") return "integer";
  for (const char* known : kParameterTypeWords)
    if (word == known) return std::string(word);
  return std::nullopt;
}

std::string substitute(std::string_view raw, const ParameterScope& scope) {
  if (raw.size() >= 3 && raw.substr(0, 2) == "${" && raw.back() == '}') {
    const std::string_view inner = raw.substr(2, raw.size() - 3);
    const ParameterLookup lookup = [&](std::string_view name) { return scope.value(name); };
    try {
      return format_number(evaluate_expression(inner, lookup));
    } catch (const ExpressionError&) {
      if (auto text = concatenate_expression(inner, lookup)) return *text;  // esmini's names ("${A_ + $x}")
      throw;
    }
  }
  if (!raw.empty() && raw.front() == '$') {
    const std::string_view name = raw.substr(1);
    if (const auto value = scope.value(name)) return *value;
    throw ExpressionError(fmt::format("unknown parameter \"{}\"", name));
  }
  return std::string(raw);
}

std::string check_parameter_value(const std::string& type, const std::string& value) {
  const auto whole_number = [&](long long low, long long high) -> std::string {
    const auto parsed = parse_whole<long long>(value);
    if (!parsed) return fmt::format("\"{}\" is not a whole number", value);
    const long long n = *parsed;
    if (n < low || n > high) return fmt::format("{} is outside [{}, {}]", value, low, high);
    return "";
  };
  if (type == "integer" || type == "int") return whole_number(-2147483648LL, 2147483647LL);
  if (type == "unsignedInt") return whole_number(0, 4294967295LL);
  if (type == "unsignedShort") return whole_number(0, 65535);
  if (type == "double") {
    return parse_whole<double>(value) ? "" : fmt::format("\"{}\" is not a number", value);
  }
  if (type == "boolean") return value == "true" || value == "false" ? "" : fmt::format("\"{}\" is not true or false", value);
  if (type == "dateTime") {
    return parse_date_time(value) ? ""
                                  : fmt::format("\"{}\" is no {}", value, kDateTimeForm);
  }
  if (type == "string") return "";
  return fmt::format("unknown parameterType \"{}\"", type);
}

}  // namespace orch::openscenario
