#include "json/object_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/suggest.hpp"
#include "json/json_text.hpp"

namespace orch {

std::string json_type_name(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return "a number";
    default: return "an unsupported value";
  }
}

ObjectReader::ObjectReader(const JsonDocument& doc, const nlohmann::json& value, std::string pointer,
                           Diagnostics& diags, std::string what)
    : doc_(doc), value_(value), pointer_(std::move(pointer)), diags_(diags), what_(std::move(what)),
      is_object_(value.is_object()) {
  if (!is_object_)
    diags_.error(doc_.where(pointer_), fmt::format("expected the {} as an object, found {}", what_,
                                                   json_type_name(value_)));
}

bool ObjectReader::has(const std::string& key) const { return is_object_ && value_.contains(key); }

SourceLocation ObjectReader::where(const std::string& key) const {
  return doc_.where(key.empty() ? pointer_ : child(key));
}

void ObjectReader::error(const std::string& key, const std::string& message) const {
  diags_.error(where(key), message);
}

void ObjectReader::warning(const std::string& key, const std::string& message) const {
  diags_.warning(where(key), message);
}

void ObjectReader::allow(const std::vector<std::string>& keys) {
  known_.insert(known_.end(), keys.begin(), keys.end());
}

void ObjectReader::already_reported(const std::vector<std::string>& keys) {
  reported_.insert(reported_.end(), keys.begin(), keys.end());
}

const nlohmann::json* ObjectReader::fetch(const std::string& key, Need need, const char* type_name,
                                          bool (*type_ok)(const nlohmann::json&)) {
  known_.push_back(key);
  if (!is_object_) return nullptr;
  auto it = value_.find(key);
  if (it == value_.end()) {
    if (need == Need::Required)
      diags_.error(where(), fmt::format("the {} needs \"{}\" ({})", what_, key, type_name));
    return nullptr;
  }
  if (!type_ok(*it)) {
    error(key, fmt::format("\"{}\" must be {}, found {}", key, type_name, json_type_name(*it)));
    return nullptr;
  }
  return &*it;
}

std::optional<double> ObjectReader::number(const std::string& key, Need need) {
  const auto* v = fetch(key, need, "a number", [](const nlohmann::json& j) { return j.is_number(); });
  if (!v) return std::nullopt;
  return v->get<double>();
}

std::optional<double> ObjectReader::number(const std::string& key, Need need, Quantity quantity) {
  const auto value = number(key, need);
  if (!value) return std::nullopt;
  if (const auto why = implausible(*value, quantity)) {
    error(key, fmt::format("\"{}\" {}", key, *why));
    return std::nullopt;
  }
  return value;
}

std::optional<int> ObjectReader::integer(const std::string& key, Need need) {
  const auto* v = fetch(key, need, "a whole number", [](const nlohmann::json& j) { return j.is_number(); });
  if (!v) return std::nullopt;
  const double d = v->get<double>();
  if (std::floor(d) != d || std::abs(d) > 2e9) {
    error(key, fmt::format("\"{}\" must be a whole number, found {}", key, json_text(*v)));
    return std::nullopt;
  }
  return static_cast<int>(d);
}

std::optional<std::string> ObjectReader::string(const std::string& key, Need need) {
  const auto* v = fetch(key, need, "a string", [](const nlohmann::json& j) { return j.is_string(); });
  if (!v) return std::nullopt;
  return v->get<std::string>();
}

std::optional<bool> ObjectReader::boolean(const std::string& key, Need need) {
  const auto* v = fetch(key, need, "true or false", [](const nlohmann::json& j) { return j.is_boolean(); });
  if (!v) return std::nullopt;
  return v->get<bool>();
}

std::optional<std::string> ObjectReader::choice(const std::string& key,
                                                const std::vector<std::string>& choices, Need need) {
  auto s = string(key, need);
  if (!s) return std::nullopt;
  if (std::find(choices.begin(), choices.end(), *s) == choices.end()) {
    error(key, fmt::format("\"{}\" is \"{}\", expected {}{}", key, *s, quoted_list(choices),
                           did_you_mean(*s, choices)));
    return std::nullopt;
  }
  return s;
}

const nlohmann::json* ObjectReader::object(const std::string& key, Need need) {
  return fetch(key, need, "an object", [](const nlohmann::json& j) { return j.is_object(); });
}

const nlohmann::json* ObjectReader::array(const std::string& key, Need need) {
  return fetch(key, need, "an array", [](const nlohmann::json& j) { return j.is_array(); });
}

void ObjectReader::finish() {
  if (!is_object_) return;
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (std::find(known_.begin(), known_.end(), it.key()) != known_.end()) continue;
    if (std::find(reported_.begin(), reported_.end(), it.key()) != reported_.end()) continue;
    std::vector<std::string> unique = known_;
    std::sort(unique.begin(), unique.end());
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    error(it.key(), fmt::format("unknown key \"{}\" in the {}{}; allowed here: {}", it.key(), what_,
                                did_you_mean(it.key(), unique), quoted_list(unique)));
  }
}

}  // namespace orch
