// `orchestrator validate FILE...`: load each scenario, find its map and waypoint file,
// check it, print every problem compiler-style and a summary line per file.
// Exit status: 0 all valid, 1 some file has errors (with --strict: or warnings),
// 2 the check itself could not run (broken map folder or catalog).
#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "cli/common.hpp"
#include "core/errors.hpp"
#include "batch/variation_batch.hpp"
#include "core/scenario_format.hpp"
#include "openscenario/scenario_check.hpp"
#include "core/suggest.hpp"
#include "core/utf8.hpp"
#include "evaluation/evaluation_file.hpp"
#include "scenario_executor/loader_internal.hpp"
#include "scenario_executor/validator.hpp"

namespace orch::cli {

namespace {

// A map's waypoint file, read once however many scenarios use the map. A file that cannot
// be read is remembered too, so that each scenario on that map reports it without rereading.
struct CachedWaypoints {
  std::optional<WaypointFile> file;
  Diagnostics problems;  // what made reading it fail
  std::string failure;   // one-line summary for the scenario's /map_id
};

class WaypointCache {
 public:
  const CachedWaypoints& get(const MapManifest& map) {
    auto it = cache_.find(map.id);
    if (it != cache_.end()) return it->second;
    CachedWaypoints entry;
    const std::string path = map.waypoint_path().string();
    try {
      entry.file = load_waypoint_file(path);
    } catch (const ScenarioError& e) {
      entry.problems = e.diagnostics();
      entry.failure = fmt::format("the waypoint file of map \"{}\" ({}) cannot be read", map.id, path);
    } catch (const MapError& e) {
      entry.failure = fmt::format("the waypoint file of map \"{}\" ({}) cannot be read: {}", map.id, path, e.what());
    }
    return cache_.emplace(map.id, std::move(entry)).first->second;
  }

 private:
  std::map<std::string, CachedWaypoints> cache_;
};

struct Shared {
  const MapRegistry& registry;
  const Catalog& catalog;
  WaypointCache& waypoints;
  ValidationOptions options;
  std::map<std::string, std::string> parameter_overrides;  // --param, OpenSCENARIO files only
};

Diagnostics validate_scenario_file(const std::string& path, Shared& shared);

// An evaluation file (docs/evaluation.md): its own keys, versions and criteria, the ego model
// it names, and the scenario it runs with everything `validate` checks of a scenario.
Diagnostics validate_evaluation_file(const std::string& path, Shared& shared) {
  LoadedEvaluation loaded = load_evaluation(path);
  Diagnostics diags = loaded.diagnostics;
  if (!loaded.file) return diags;
  const EvaluationFile& f = *loaded.file;
  if (!f.vehicle_model.empty() && !shared.catalog.find(f.vehicle_model))
    diags.error(SourceLocation{path, "/VehicleModel", 0},
                fmt::format("VehicleModel \"{}\" is not a model of the catalog", f.vehicle_model));
  diags.append(validate_scenario_file(f.scenario_file, shared));
  return diags;
}

Diagnostics validate_file(const std::string& path, Shared& shared) {
  return is_evaluation_file(path) ? validate_evaluation_file(path, shared) : validate_scenario_file(path, shared);
}

Diagnostics validate_scenario_file(const std::string& path, Shared& shared) {
  if (batch::is_variation_input(path)) return batch::check_variation_file(path);  // *_variation.xosc
  if (detect_scenario_format(path) == ScenarioFormat::OpenScenario)
    return openscenario::check_scenario_file(path, {shared.parameter_overrides});
  Diagnostics diags;
  try {
    const JsonDocument doc = JsonDocument::load(path);
    // The best-effort model: references are checked even when the file has other errors,
    // so that one run reports everything (see loader_internal.hpp).
    const auto read = scenario_loading::read_scenario(doc, diags);
    const scenario::Scenario& s = read.scenario;
    // Without the map's waypoints, everything but wp_id / wp_idx is still checked.
    static const WaypointFile kNoWaypoints;
    const WaypointFile* waypoints = &kNoWaypoints;
    const MapManifest* map = shared.registry.find(s.map_id);
    if (s.map_id.empty()) {
      // a missing map_id is reported by the loader
    } else if (map) {
      const CachedWaypoints& cached = shared.waypoints.get(*map);
      if (cached.file) {
        waypoints = &*cached.file;
      } else {
        diags.error(doc.where("/map_id"), cached.failure);
        diags.append(cached.problems);
      }
    } else {
      const auto known = shared.registry.ids();
      diags.error(doc.where("/map_id"),
                  fmt::format("no map \"{}\"{}; known maps: {} (map folders are searched in --maps, $ORCH_MAPS "
                              "and sumo_nets/)",
                              s.map_id, did_you_mean(s.map_id, known), known.empty() ? "none" : quoted_list(known)));
    }
    if (read.skeleton_complete) diags.append(check_scenario(s, *waypoints, shared.catalog, shared.options));
  } catch (const ScenarioError& e) {  // unreadable file, invalid JSON, duplicate key
    diags.append(e.diagnostics());
  } catch (const MapError& e) {
    diags.error(SourceLocation{path, "/map_id", 0}, e.what());
  }
  return diags;
}

// Loader and checks find problems in two passes; users read files top to bottom.
// Messages about other files (a broken waypoint file) come last.
std::vector<Diagnostic> in_file_order(const Diagnostics& diags, const std::string& path) {
  std::vector<Diagnostic> items = diags.items();
  std::stable_sort(items.begin(), items.end(), [&](const Diagnostic& a, const Diagnostic& b) {
    return std::pair(a.where.file != path, a.where.line) < std::pair(b.where.file != path, b.where.line);
  });
  return items;
}

std::string plural(int n, const char* word) { return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s"); }

}  // namespace

int validate_command(const ValidateOptions& o) {
  std::optional<MapRegistry> registry;
  std::optional<Catalog> catalog;
  try {
    registry.emplace(make_registry(o.common));
    catalog.emplace(load_catalog(o.common));
  } catch (const ScenarioError& e) {  // a broken map.json or --catalog file
    std::cerr << e.diagnostics().format() << "validate: cannot check scenarios without the maps and the catalog\n";
    return 2;
  } catch (const OrchError& e) {
    std::cerr << "validate: " << valid_utf8(e.what()) << "\n";
    return 2;
  }

  WaypointCache waypoints;
  std::map<std::string, std::string> parameters;
  try {
    parameters = openscenario::parse_parameter_overrides(o.parameters);
  } catch (const OrchError& e) {
    std::cerr << "validate: " << e.what() << "\n";
    return 2;
  }
  Shared shared{*registry, *catalog, waypoints, ValidationOptions{o.strict}, parameters};
  int failed = 0;
  for (const auto& path : o.files) {
    const Diagnostics diags = validate_file(path, shared);
    for (const auto& d : in_file_order(diags, path))
      if (!o.quiet || d.severity == Severity::Error) std::cout << d.format() << "\n";
    const bool bad = diags.has_errors() || (o.strict && diags.warning_count() > 0);
    failed += bad ? 1 : 0;
    std::cout << fmt::format("{}: {}, {}, {}\n", valid_utf8(path), bad ? "INVALID" : "valid", plural(diags.error_count(), "error"),
                             plural(diags.warning_count(), "warning"));
  }
  if (o.files.size() > 1)
    std::cout << fmt::format("{} checked: {} valid, {} invalid\n", plural(static_cast<int>(o.files.size()), "file"),
                             static_cast<int>(o.files.size()) - failed, failed);
  return failed > 0 ? 1 : 0;
}

}  // namespace orch::cli
