#pragma once
// Parameter scopes and attribute value substitution: "$name" stands for a parameter's
// value, "${...}" for an expression's (expression.hpp). A scope sees its parent's
// parameters unless it declares the same name (catalog entries, Stories and Maneuvers over
// the scenario: the innermost declaration of a name is the one used).
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace orch::openscenario {

class ParameterScope {
 public:
  explicit ParameterScope(const ParameterScope* parent = nullptr) : parent_(parent) {}
  // `key` names the parameter in the storyboard runtime (ParameterSetAction,
  // ParameterCondition): the name for the scenario's own, "<Story or Maneuver>/<name>" for
  // a local one, "" for one the runtime does not hold (catalog entries).
  void set(const std::string& name, const std::string& type, const std::string& value, std::string key = "") {
    values_[name] = Entry{type, value, std::move(key)};
  }
  // Keeps the key of the name's declaration in this scope (a --param override, an assignment).
  void assign(const std::string& name, const std::string& value) { values_.at(name).value = value; }
  [[nodiscard]] bool declares(const std::string& name) const { return values_.contains(name); }
  [[nodiscard]] std::optional<std::string> value(std::string_view name) const;
  [[nodiscard]] std::optional<std::string> type(std::string_view name) const;
  [[nodiscard]] std::optional<std::string> key(std::string_view name) const;

 private:
  struct Entry {
    std::string type;
    std::string value;
    std::string key;
  };
  [[nodiscard]] const Entry* find(std::string_view name) const;
  const ParameterScope* parent_;
  std::map<std::string, Entry, std::less<>> values_;
};

// The attribute text after substitution; throws ExpressionError (the caller adds the place)
// for an unknown parameter or a bad expression.
std::string substitute(std::string_view raw, const ParameterScope& scope);

// The parameter types of every revision: 1.2 renamed "integer" to "int" (the old name stays
// valid); both are read as "integer". nullopt for a word that is no type.
std::optional<std::string> parameter_type(std::string_view word);
inline const char* const kParameterTypeWords[] = {"int",           "integer", "double",  "string",
                                                  "unsignedInt",   "unsignedShort", "boolean", "dateTime"};

// Whether `value` is a valid text of the parameter type; "" when it is, else what is wrong.
std::string check_parameter_value(const std::string& type, const std::string& value);

}  // namespace orch::openscenario
