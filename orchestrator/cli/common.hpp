#pragma once
// Pieces several subcommands share: finding maps, loading the catalog.
#include <filesystem>
#include <string>

#include "cli/commands.hpp"
#include "map/map_registry.hpp"
#include "scenario_executor/catalog.hpp"

namespace orch::cli {

MapRegistry make_registry(const CommonOptions& c);
Catalog load_catalog(const CommonOptions& c);
// A map named by id/alias, or a folder holding map.json. Throws MapError listing the
// known maps (with "did you mean") when there is no such map.
MapManifest resolve_map(const MapRegistry& registry, const std::string& id_or_folder);

}  // namespace orch::cli
