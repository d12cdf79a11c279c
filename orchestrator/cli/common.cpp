#include "cli/common.hpp"

#include "core/errors.hpp"
#include "core/suggest.hpp"

namespace orch::cli {

MapRegistry make_registry(const CommonOptions& c) {
  std::vector<std::filesystem::path> dirs(c.map_dirs.begin(), c.map_dirs.end());
  if (dirs.empty()) dirs = MapRegistry::default_search_dirs();
  return MapRegistry(dirs);
}

Catalog load_catalog(const CommonOptions& c) {
  return c.catalog.empty() ? Catalog::embedded() : Catalog::load(c.catalog);
}

MapManifest resolve_map(const MapRegistry& registry, const std::string& id_or_folder) {
  if (const auto* m = registry.find(id_or_folder)) return *m;
  if (std::filesystem::exists(std::filesystem::path(id_or_folder) / "map.json"))
    return load_map_manifest(id_or_folder);
  throw MapError("no map \"" + id_or_folder + "\"" + did_you_mean(id_or_folder, registry.ids()) +
                 "; known maps: " + quoted_list(registry.ids()));
}

}  // namespace orch::cli
