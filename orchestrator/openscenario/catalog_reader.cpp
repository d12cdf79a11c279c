// CatalogLocations, catalog files and CatalogReference resolution.
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace fs = std::filesystem;

namespace {

void load_catalog_file(const fs::path& file, Context& context) {
  auto source = std::make_unique<xml::XmlSource>(xml::XmlSource::load(file.string()));
  Element root(*source, source->root(), context.global);
  if (root.name() != "OpenSCENARIO") root.fail(fmt::format("expected OpenSCENARIO, found {}", root.name()));
  root.ignore_children({"FileHeader"});
  Element catalog = root.child("Catalog");
  root.finish();
  const std::string name = catalog.text("name");
  auto& entries = context.catalogs[name];
  for (const pugi::xml_node entry : catalog.node().children()) {
    if (entry.type() != pugi::node_element) continue;
    const std::string entry_name = entry.attribute("name").as_string();
    if (entry_name.empty()) source->fail(entry, "catalog entry without a name");
    if (!entries.emplace(entry_name, CatalogEntry{source.get(), entry}).second)
      source->fail(entry, fmt::format("catalog {} holds two entries named {}", name, entry_name));
  }
  context.catalog_files.push_back(std::move(source));
}

// A catalog entry's declaration, read for the CatalogReference `reference`: an error in it
// also names the reference (the file the user runs), not only the catalog's line.
Parameter read_with_reference(Element& d, const Element& reference, const std::string& entry_name) {
  try {
    return read_declaration(d);
  } catch (const ScenarioError& e) {
    Diagnostics both = e.diagnostics();
    const Place at = reference.place();
    both.error(SourceLocation{reference.source().file(), at.path, at.line},
               fmt::format("the CatalogReference to catalog entry \"{}\", whose ParameterDeclaration (the other "
                           "error) is invalid", entry_name));
    throw ScenarioError(std::move(both));
  }
}

}  // namespace

void read_catalog_locations(Element& locations, const std::string& scenario_dir, Context& context) {
  static const std::vector<std::string> kinds = {"VehicleCatalog", "ControllerCatalog", "PedestrianCatalog",
                                                 "MiscObjectCatalog", "EnvironmentCatalog", "ManeuverCatalog",
                                                 "TrajectoryCatalog", "RouteCatalog"};
  for (const std::string& kind : kinds) {
    for (Element location : locations.children(kind.c_str())) {
      Element directory = location.child("Directory");
      location.finish();
      const std::string path = directory.text("path");
      directory.finish();
      fs::path dir = fs::path(path).is_absolute() ? fs::path(path) : fs::path(scenario_dir) / path;
      std::error_code ec;
      if (!fs::is_directory(dir, ec)) {
        // The file may not use this catalog: only a reference into it is an error (resolve).
        const std::string shown = dir.lexically_normal().string();
        context.warnings.warning(directory.source().where(directory.node(), "path"),
                                 fmt::format("no directory {} ({}); a reference into it will fail", shown, kind));
        context.missing_catalog_directories[kind] = shown;
        continue;
      }
      std::vector<fs::path> files;
      for (const auto& f : fs::directory_iterator(dir))
        if (f.path().extension() == ".xosc") files.push_back(f.path());
      std::sort(files.begin(), files.end());  // deterministic whatever the file system lists
      for (const fs::path& f : files) load_catalog_file(f, context);
    }
  }
  locations.finish();
}

// The standard resolves a CatalogReference by the Catalog's `name`. Files written for esmini
// (which looks an entry up among the catalogs of the kind it needs) may name a catalog that
// does not exist, e.g. "MiscObjectCatalog" for a file whose Catalog is named "MiscObject".
// Where exactly one loaded catalog holds an entry of that name and of a kind the reference
// needs, it is used, with a warning; otherwise the reference stays an error.
std::map<std::string, std::map<std::string, CatalogEntry>>::iterator Context::find_by_kind(
    Element& reference, const std::string& catalog_name, const std::string& entry_name,
    const std::vector<std::string>& kinds) {
  auto found = catalogs.end();
  int matches = 0;
  for (auto it = catalogs.begin(); it != catalogs.end(); ++it) {
    const auto entry = it->second.find(entry_name);
    if (entry == it->second.end()) continue;
    if (std::find(kinds.begin(), kinds.end(), entry->second.node.name()) == kinds.end()) continue;
    found = it;
    ++matches;
  }
  if (matches != 1) return catalogs.end();
  warnings.warning(reference.source().where(reference.node(), "catalogName"),
                   fmt::format("no catalog named \"{}\" (the standard resolves catalogName by the Catalog's name); "
                               "its entry \"{}\" is taken from catalog \"{}\", the one that holds such an entry, "
                               "as esmini does",
                               catalog_name, entry_name, found->first));
  return found;
}

Element Context::resolve(Element& reference, const std::vector<std::string>& kinds) {
  const std::string catalog_name = reference.text("catalogName");
  const std::string entry_name = reference.text("entryName");
  auto catalog = catalogs.find(catalog_name);
  if (catalog == catalogs.end()) catalog = find_by_kind(reference, catalog_name, entry_name, kinds);
  if (catalog == catalogs.end()) {
    std::vector<std::string> names;
    for (const auto& [n, c] : catalogs) names.push_back(n);
    std::string missing;
    for (const auto& [kind, dir] : missing_catalog_directories)
      missing += fmt::format("; the {} directory {} does not exist", kind, dir);
    reference.fail_attribute("catalogName", fmt::format("no catalog named \"{}\" in the CatalogLocations{}{}",
                                                        catalog_name, did_you_mean(catalog_name, names), missing));
  }
  const auto entry = catalog->second.find(entry_name);
  if (entry == catalog->second.end()) {
    std::vector<std::string> names;
    for (const auto& [n, e] : catalog->second) names.push_back(n);
    reference.fail_attribute("entryName", fmt::format("catalog \"{}\" has no entry \"{}\"{}", catalog_name,
                                                      entry_name, did_you_mean(entry_name, names)));
  }
  const CatalogEntry& found = entry->second;
  if (std::find(kinds.begin(), kinds.end(), found.node.name()) == kinds.end())
    reference.fail(fmt::format("catalog entry \"{}\" is a {}, expected {}", entry_name, found.node.name(),
                               quoted_list(kinds)));
  // The entry's own parameters, with the reference's assignments (evaluated where the
  // reference stands) replacing their defaults.
  ParameterScope& scope = entry_scopes.emplace_back(&global);
  Element entry_element(*found.source, found.node, scope);
  std::vector<std::string> declared;
  if (auto declarations = entry_element.optional_child("ParameterDeclarations")) {
    for (Element d : declarations->children("ParameterDeclaration")) {
      const Parameter p = read_with_reference(d, reference, entry_name);
      scope.set(p.name, p.type, p.value, "");  // the runtime does not change an entry's parameters
      declared.push_back(p.name);
      d.finish();
    }
    declarations->finish();
  }
  if (auto assignments = reference.optional_child("ParameterAssignments")) {
    for (Element a : assignments->children("ParameterAssignment")) {
      // parameterRef is the entry's parameter's name; "$name" (which, read as a parameter
      // reference, would be a value of the scenario's) is read as the name where the entry
      // declares it, as the peer player esmini does and its example files write it.
      const std::string raw = a.node().attribute("parameterRef").value();
      std::string name;
      if (raw.size() > 1 && raw.front() == '$' && scope.declares(raw.substr(1))) {
        name = raw.substr(1);
        a.ignore_attributes({"parameterRef"});
      } else {
        name = a.text("parameterRef");
      }
      if (!scope.declares(name))
        a.fail_attribute("parameterRef", fmt::format("catalog entry \"{}\" declares no parameter \"{}\"{}",
                                                     entry_name, name, did_you_mean(name, declared)));
      const std::string value = a.text("value");
      const std::string problem = check_parameter_value(*scope.type(name), value);
      if (!problem.empty())
        a.fail_attribute("value", fmt::format("catalog entry \"{}\" declares parameter \"{}\" as {}, but the value "
                                              "assigned to it {}", entry_name, name, *scope.type(name), problem));
      scope.assign(name, value);
      a.finish();
    }
    assignments->finish();
  }
  reference.finish();
  return entry_element;
}

}  // namespace orch::openscenario::reading
