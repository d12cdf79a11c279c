#pragma once
// Parameter scopes and attribute value substitution: "$name" stands for a parameter's
// value, "${...}" for an expression's (expression.hpp). A scope sees its parent's
// parameters unless it declares the same name (catalog entries over the scenario).
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace orch::openscenario {

class ParameterScope {
 public:
  explicit ParameterScope(const ParameterScope* parent = nullptr) : parent_(parent) {}
  void set(const std::string& name, const std::string& type, const std::string& value) {
    values_[name] = Entry{type, value};
  }
  [[nodiscard]] bool declares(const std::string& name) const { return values_.contains(name); }
  [[nodiscard]] std::optional<std::string> value(std::string_view name) const;
  [[nodiscard]] std::optional<std::string> type(std::string_view name) const;

 private:
  struct Entry {
    std::string type;
    std::string value;
  };
  const ParameterScope* parent_;
  std::map<std::string, Entry, std::less<>> values_;
};

// The attribute text after substitution; throws ExpressionError (the caller adds the place)
// for an unknown parameter or a bad expression.
std::string substitute(std::string_view raw, const ParameterScope& scope);

// Whether `value` is a valid text of the parameter type; "" when it is, else what is wrong.
std::string check_parameter_value(const std::string& type, const std::string& value);

}  // namespace orch::openscenario
