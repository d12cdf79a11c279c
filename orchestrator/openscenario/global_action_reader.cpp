// ParameterAction (SetAction, ModifyAction with AddValue / MultiplyByValue rules). The
// EntityAction readers are in the global table of action_reader.cpp.
#include <fmt/format.h>

#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

// The declared parameter `parameterRef` names, with its type.
std::pair<std::string, std::string> declared_parameter(Element& parameter_action) {
  const std::string name = parameter_action.text("parameterRef");
  const auto type = parameter_action.scope().type(name);
  if (!type) parameter_action.fail_attribute("parameterRef", fmt::format("no parameter \"{}\" is declared", name));
  return {name, *type};
}

}  // namespace

ParameterSetAction read_parameter_set(Element& parameter_action, Element& set) {
  const auto [name, type] = declared_parameter(parameter_action);
  ParameterSetAction a{name, set.text("value")};
  const std::string problem = check_parameter_value(type, a.value);
  if (!problem.empty()) set.fail_attribute("value", fmt::format("{} ({} parameter {})", problem, type, name));
  return a;
}

ParameterModifyAction read_parameter_modify(Element& parameter_action, Element& modify) {
  const auto [name, type] = declared_parameter(parameter_action);
  if (type != "double" && type != "integer" && type != "unsignedInt" && type != "unsignedShort")
    parameter_action.fail_attribute("parameterRef",
                                    fmt::format("ParameterModifyAction needs a numeric parameter; {} is a {}", name, type));
  Element holder = modify.child("Rule");
  Element rule = holder.one_of({"AddValue", "MultiplyByValue"});
  holder.finish();
  ParameterModifyAction a{name, rule.name() == "MultiplyByValue", rule.number("value")};
  rule.finish();
  return a;
}

}  // namespace orch::openscenario::reading
