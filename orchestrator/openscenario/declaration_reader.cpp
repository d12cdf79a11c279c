// ParameterDeclarations and VariableDeclarations: one declaration's name, type and value,
// and the parameter scopes that Stories, Maneuvers and inline objects open with their own
// declarations (ASAM OpenSCENARIO: a parameter is visible in the element declaring it and
// everything inside; an inner declaration of a name hides an outer one).
#include <set>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {

Parameter read_declaration(Element& d, const char* type_attribute) {
  Parameter p;
  p.name = d.text("name");
  const std::string word = d.text(type_attribute);
  const auto type = parameter_type(word);
  if (!type) {
    const std::vector<std::string> words(std::begin(kParameterTypeWords), std::end(kParameterTypeWords));
    d.fail_attribute(type_attribute, fmt::format("expected one of {}, found \"{}\"{}", quoted_list(words), word,
                                                 did_you_mean(word, words)));
  }
  p.type = *type;
  p.value = d.text("value");
  const std::string problem = check_parameter_value(p.type, p.value);
  // The standard gives a declaration "a default, type-specific initialization value" (1.3,
  // 9.1 Parameters): a value its type cannot hold is an error, wherever it is used.
  if (!problem.empty())
    d.fail_attribute("value", fmt::format("parameter \"{}\" is declared {}, but its value {} (a declaration's value is "
                                          "\"a default, type-specific initialization value\", ASAM OpenSCENARIO 9.1; "
                                          "declare it with the type its value has)",
                                          p.name, word, problem));
  return p;
}

Element open_scope(Element& owner, Context& context, const std::string& key_prefix) {
  auto declarations = owner.optional_child("ParameterDeclarations");
  if (!declarations) return owner;
  ParameterScope& scope = context.entry_scopes.emplace_back(&owner.scope());
  Element inner = declarations->scoped(scope);  // a value may use the declarations before it
  std::set<std::string> names;
  for (Element d : inner.children("ParameterDeclaration")) {
    Parameter p = read_declaration(d);
    if (!names.insert(p.name).second)
      d.fail_attribute("name", fmt::format("parameter \"{}\" is declared twice", p.name));
    const std::string key = key_prefix.empty() ? "" : key_prefix + "/" + p.name;
    scope.set(p.name, p.type, p.value, key);
    if (!key.empty()) {
      p.name = key;
      context.local_parameters.push_back(p);
    }
    d.finish();
  }
  inner.finish();
  return owner.scoped(scope);
}

}  // namespace orch::openscenario::reading
