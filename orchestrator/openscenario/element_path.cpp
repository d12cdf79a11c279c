#include "openscenario/element_path.hpp"

#include <algorithm>

namespace orch::openscenario {

std::vector<std::string> split_path(const std::string& reference) {
  std::vector<std::string> names;
  std::size_t from = 0;
  for (std::size_t at = reference.find("::"); at != std::string::npos; at = reference.find("::", from)) {
    names.push_back(reference.substr(from, at - from));
    from = at + 2;
  }
  names.push_back(reference.substr(from));
  return names;
}

std::string join_path(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) joined += (joined.empty() ? "" : "::") + name;
  return joined;
}

ReferenceMatch resolve_reference(const std::string& reference,
                                 const std::vector<std::pair<std::vector<std::string>, std::string>>& elements) {
  const std::vector<std::string> wanted = split_path(reference);
  ReferenceMatch match;
  for (const auto& [path, key] : elements)
    if (path.size() >= wanted.size() && std::equal(wanted.rbegin(), wanted.rend(), path.rbegin()))
      match.keys.push_back(key);
  // A name written whole, "::" and all, that is itself an element's name (names may hold "::").
  if (match.keys.empty() && wanted.size() > 1)
    for (const auto& [path, key] : elements)
      if (!path.empty() && path.back() == reference) match.keys.push_back(key);
  return match;
}

}  // namespace orch::openscenario
