#pragma once
// A YAML file as a JsonDocument: the value tree (plain scalars typed as YAML 1.2's core
// schema does: null, true/false, integers, floats; quoted scalars stay strings) and the line
// of every value, so evaluation files are read and reported like the JSON files
// (ObjectReader: unknown keys with "did you mean", file:line: error: /pointer: message).
#include <string>

#include "json/json_document.hpp"

namespace orch {

// Throws ScenarioError (file, line) on unreadable or invalid YAML, a repeated key, or a key
// that is not a plain scalar.
JsonDocument load_yaml_document(const std::string& path);
JsonDocument parse_yaml_document(const std::string& text, const std::string& path_for_messages);

}  // namespace orch
