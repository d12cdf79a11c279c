// Storyboard element names and the references to them (StoryboardElementStateCondition's
// storyboardElementRef). The standard allows one name in different parents and a reference
// qualified by the names of its parents, separated by "::" (docs/openscenario.md, "Names of
// storyboard elements").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace orch::openscenario {

// "a::b::c" -> {"a", "b", "c"}; a name without "::" -> {name}.
std::vector<std::string> split_path(const std::string& reference);
std::string join_path(const std::vector<std::string>& names);

struct ReferenceMatch {
  std::vector<std::string> keys;  // the keys of every element the reference names, in file order
};

// The elements (path of names from the Story down, key) that `reference` names: those whose
// path ends with the reference's names. A plain name matches every element of that name; a
// qualified one ("event::action") only those under such parents. More than one key: ambiguous.
ReferenceMatch resolve_reference(const std::string& reference,
                                 const std::vector<std::pair<std::vector<std::string>, std::string>>& elements);

}  // namespace orch::openscenario
