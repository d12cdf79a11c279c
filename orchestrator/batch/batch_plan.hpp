#pragma once
// What a batch runs: every parameter set of the given logical scenarios / parameter files,
// each bound into its template and checked before anything starts, optionally cut to one
// shard. The plan is written to batch.json (manifest.hpp) in the output folder; a resumed
// batch plans again from the same inputs and refuses to go on when they have changed since.
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "batch/logical_scenario.hpp"
#include "batch/parameter_file.hpp"
#include "batch/variation_batch.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

// `--shard K/N`: the K-th (1-based) of N shards.
struct Shard {
  int index = 1;
  int count = 1;
  [[nodiscard]] std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// Throws OrchError for anything but "K/N" with 1 <= K <= N.
Shard parse_shard(const std::string& text);

// Where a logical scenario came from: the seed's abstract and natural-language files,
// linked when they sit beside the logical file.
struct Lineage {
  std::string abstract_uuid;  // the logical's parent_abstract_uuid ("" = none)
  std::filesystem::path abstract_file;  // empty when not found
  std::string natural_uuid;
  std::filesystem::path natural_file;
  std::string original_prompt;
};

struct PlannedRun {
  std::string id;  // {logical_uuid}_{parameter_uuid}
  std::string logical_uuid;
  std::string parameter_uuid;
  std::string name;  // the logical scenario's name
  std::size_t logical_index = 0;  // into BatchPlan::logicals
  ParameterSet set;
};

struct PlannedLogical {
  LogicalScenario logical;
  std::filesystem::path parameter_file;
  Lineage lineage;
  // The template, loaded and checked once when planning; every set is bound into it.
  std::shared_ptr<const JsonDocument> template_doc;
  // An OpenSCENARIO parameter variation (variation_batch.hpp) in place of a template: its
  // runs are the referenced scenario with --param values. Null for JSON logical scenarios.
  std::shared_ptr<const VariationLogical> variation;
};

struct BatchPlan {
  std::vector<std::string> inputs;  // absolute paths as resolved
  std::vector<PlannedLogical> logicals;
  std::vector<PlannedRun> runs;  // this shard's runs, in input and file order
  std::size_t total_runs = 0;    // before sharding
  std::optional<Shard> shard;
  // sha256 of every file the runs depend on (logical, parameter, template files).
  std::vector<std::pair<std::string, std::string>> input_hashes;
};

// Throws ScenarioError / OrchError naming the file and the problem: an input that is neither
// a logical scenario nor a parameter file, a logical scenario never sampled, a parameter set
// that does not bind, ...
BatchPlan plan_batch(const std::vector<std::string>& inputs, const std::optional<Shard>& shard);

// Shard membership: runs sorted by id, the i-th (0-based) belongs to shard i % N + 1, so
// shards are balanced and independent of the order the inputs were given in.
bool in_shard(const std::vector<std::string>& sorted_ids, const std::string& id, const Shard& shard);

}  // namespace orch::batch
