#pragma once
// The parameter file (ATLAS `logical_{uuid}_parameters.json`, shared/seeds/003): concrete
// values sampled from one logical scenario, one entry per parameter set, each with its seed.
// In place of the seed's `carla_config` each set has a `sumo_config` (map, step, max_time,
// traffic, backend): everything `orchestrator run` needs besides the scenario.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

struct SumoConfig {
  std::string map;  // the bound scenario's map_id, for the record
  double step = 0.05;
  std::optional<double> max_time;
  std::optional<std::string> traffic;  // passed to `run --traffic` (when run has it)
  std::optional<std::string> backend;  // passed to `run --backend` (when run has it)
};

struct ParameterSet {
  std::string uuid;
  std::string created_at;
  std::optional<long long> seed;  // optional in the seed's format; also SUMO's seed for the run
  nlohmann::json sampled_values;  // {"group": {"name": value}}
  SumoConfig sumo_config;
  nlohmann::json output;          // as read; written back as output_block() (it follows from the ids)
  SourceLocation where;
};

struct ParameterFile {
  std::filesystem::path file;
  std::string logical_uuid;
  std::string created_at;
  std::vector<ParameterSet> sets;  // in the order of the file

  [[nodiscard]] const ParameterSet* find(const std::string& uuid) const;
};

bool is_parameter_file(const JsonDocument& doc);
// Throws ScenarioError with every problem (file, line, pointer).
ParameterFile load_parameter_file(const std::filesystem::path& file);
ParameterFile read_parameter_file(const JsonDocument& doc);
// The file's text, sets in order, keys in the seed's order.
std::string to_json_text(const ParameterFile& f);

// Run id of a parameter set in a batch: "{logical_uuid}_{parameter_uuid}", the seed's
// naming of execution traces and outputs.
std::string run_id(const std::string& logical_uuid, const std::string& parameter_uuid);
// The `output` block of a set: run folder, result, trace and execution trace, relative to
// the batch's output folder.
nlohmann::ordered_json output_block(const std::string& logical_uuid, const std::string& parameter_uuid);

}  // namespace orch::batch
