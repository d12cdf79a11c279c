#pragma once
// batch.json, the first file of a batch folder: the inputs, the shard, the options, a
// sha256 of every input file and the id of every run the folder is to hold. `--resume`
// reads it to plan the same runs again; reports and merges read it to know which runs are
// missing.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "batch/batch_plan.hpp"

namespace orch::batch {

struct PlannedEntry {
  std::string id;
  std::string logical_uuid;
  std::string parameter_uuid;
  std::string name;
  std::filesystem::path batch_dir;
};

struct Manifest {
  std::filesystem::path batch_dir;
  std::vector<std::string> inputs;
  std::optional<Shard> shard;
  std::size_t total_runs = 0;
  nlohmann::json options;  // as the batch was started: jobs, timeout_s, retries, maps, ...
  std::map<std::string, std::string> input_sha256;
  std::vector<PlannedEntry> runs;
};

std::filesystem::path manifest_path(const std::filesystem::path& batch_dir);
std::string manifest_text(const BatchPlan& plan, const nlohmann::ordered_json& options);
// Throws OrchError when the folder holds no batch.json, ScenarioError when it is broken.
Manifest read_manifest(const std::filesystem::path& batch_dir);

}  // namespace orch::batch
