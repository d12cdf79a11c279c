#pragma once
// Reads one JSON object of a user file against its expected keys: missing required keys,
// wrong types and unknown keys (with "did you mean") all become diagnostics with file,
// line and JSON pointer, and reading goes on so that one pass reports every problem.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/plausible.hpp"
#include "json/json_document.hpp"

namespace orch {

enum class Need { Required, Optional };

class ObjectReader {
 public:
  // `what` names the object in messages, e.g. "speed condition".
  ObjectReader(const JsonDocument& doc, const nlohmann::json& value, std::string pointer,
               Diagnostics& diags, std::string what);

  [[nodiscard]] bool is_object() const { return is_object_; }
  [[nodiscard]] bool has(const std::string& key) const;
  [[nodiscard]] const std::string& pointer() const { return pointer_; }
  [[nodiscard]] std::string child(const std::string& key) const { return json_pointer_child(pointer_, key); }
  [[nodiscard]] SourceLocation where(const std::string& key = {}) const;
  [[nodiscard]] const JsonDocument& doc() const { return doc_; }
  [[nodiscard]] Diagnostics& diags() const { return diags_; }

  std::optional<double> number(const std::string& key, Need need);
  // A number that stands for a physical quantity: a magnitude no map or run can mean
  // (core/plausible.hpp) is an error naming the key, and the value is not returned.
  std::optional<double> number(const std::string& key, Need need, Quantity quantity);
  // A whole number (ids); 3.0 is accepted, 3.5 is an error.
  std::optional<int> integer(const std::string& key, Need need);
  std::optional<std::string> string(const std::string& key, Need need);
  std::optional<bool> boolean(const std::string& key, Need need);
  // One of a closed set of strings; a near miss gets "did you mean".
  std::optional<std::string> choice(const std::string& key, const std::vector<std::string>& choices,
                                    Need need);
  const nlohmann::json* object(const std::string& key, Need need);
  const nlohmann::json* array(const std::string& key, Need need);
  // Declares keys that are valid here even when this reader does not read them.
  void allow(const std::vector<std::string>& keys);
  // Keys the caller reported itself (a key that belongs elsewhere): finish() neither
  // reports them again nor lists them among the keys allowed here.
  void already_reported(const std::vector<std::string>& keys);
  // Reports every key present but neither read nor allowed. Call once, after reading.
  void finish();

  void error(const std::string& key, const std::string& message) const;
  void warning(const std::string& key, const std::string& message) const;

 private:
  const nlohmann::json* fetch(const std::string& key, Need need, const char* type_name,
                              bool (*type_ok)(const nlohmann::json&));

  const JsonDocument& doc_;
  const nlohmann::json& value_;
  std::string pointer_;
  Diagnostics& diags_;
  std::string what_;
  bool is_object_;
  std::vector<std::string> known_;
  std::vector<std::string> reported_;
};

// Name of a JSON value's type for messages ("a string", "an array", ...).
std::string json_type_name(const nlohmann::json& v);

}  // namespace orch
