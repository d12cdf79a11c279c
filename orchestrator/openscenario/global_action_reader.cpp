// ParameterAction (SetAction, ModifyAction with AddValue / MultiplyByValue rules) and 1.2's
// VariableAction (the same on a variable). The EntityAction readers are in the global table
// of action_reader.cpp.
#include <algorithm>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

bool numeric(const std::string& type) {
  return type == "double" || type == "integer" || type == "unsignedInt" || type == "unsignedShort";
}

}  // namespace

std::pair<std::string, std::string> runtime_parameter(Element& at, const char* attribute) {
  const std::string name = at.text(attribute);
  const auto type = at.scope().type(name);
  if (!type) at.fail_attribute(attribute, fmt::format("no parameter \"{}\" is declared", name));
  const std::string key = at.scope().key(name).value_or("");
  if (key.empty())
    at.fail_attribute(attribute, fmt::format("parameter \"{}\" is a catalog entry's: its value cannot change while "
                                             "the scenario runs (not supported)", name));
  return {key, *type};
}

std::pair<std::string, std::string> declared_variable(Element& at, const Context& context) {
  const std::string name = at.text("variableRef");
  const auto it = std::find_if(context.variables.begin(), context.variables.end(),
                               [&](const Parameter& v) { return v.name == name; });
  if (it == context.variables.end()) {
    std::vector<std::string> names;
    for (const Parameter& v : context.variables) names.push_back(v.name);
    at.fail_attribute("variableRef", fmt::format("no variable \"{}\" is declared (VariableDeclarations){}", name,
                                                 did_you_mean(name, names)));
  }
  return {name, it->type};
}

ParameterSetAction read_parameter_set(Element& parameter_action, Element& set) {
  const auto [name, type] = runtime_parameter(parameter_action, "parameterRef");
  ParameterSetAction a{name, set.text("value")};
  const std::string problem = check_parameter_value(type, a.value);
  if (!problem.empty()) set.fail_attribute("value", fmt::format("{} ({} parameter {})", problem, type, name));
  return a;
}

ParameterModifyAction read_parameter_modify(Element& parameter_action, Element& modify) {
  const auto [name, type] = runtime_parameter(parameter_action, "parameterRef");
  if (!numeric(type))
    parameter_action.fail_attribute("parameterRef",
                                    fmt::format("ParameterModifyAction needs a numeric parameter; {} is a {}", name, type));
  Element holder = modify.child("Rule");
  Element rule = holder.one_of({"AddValue", "MultiplyByValue"});
  holder.finish();
  ParameterModifyAction a{name, rule.name() == "MultiplyByValue", rule.number("value")};
  rule.finish();
  return a;
}

VariableSetAction read_variable_set(Element& variable_action, Element& set, const Context& context) {
  const auto [name, type] = declared_variable(variable_action, context);
  VariableSetAction a{name, set.text("value")};
  const std::string problem = check_parameter_value(type, a.value);
  if (!problem.empty()) set.fail_attribute("value", fmt::format("{} ({} variable {})", problem, type, name));
  return a;
}

VariableModifyAction read_variable_modify(Element& variable_action, Element& modify, const Context& context) {
  const auto [name, type] = declared_variable(variable_action, context);
  if (!numeric(type))
    variable_action.fail_attribute("variableRef",
                                   fmt::format("VariableModifyAction needs a numeric variable; {} is a {}", name, type));
  Element holder = modify.child("Rule");
  Element rule = holder.one_of({"AddValue", "MultiplyByValue"});
  holder.finish();
  VariableModifyAction a{name, rule.name() == "MultiplyByValue", rule.number("value")};
  rule.finish();
  return a;
}

}  // namespace orch::openscenario::reading
