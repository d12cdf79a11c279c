#pragma once
// A logical scenario (ATLAS `logical_{uuid}.json`, shared/seeds/003): parameter
// distributions only, never concrete values, plus the template scenario they are bound
// into. Read once into plain values; every problem is reported with file, line and pointer.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/diagnostics.hpp"
#include "json/json_document.hpp"

namespace orch::batch {

enum class ValueType { Float, Int, String, Bool };
const char* type_name(ValueType t);

// The seed's four distributions. Values of `constant` and `choice` keep their JSON type.
struct Constant {
  nlohmann::json value;
};
struct Uniform {
  double min = 0;
  double max = 0;  // float: [min, max); int: every whole number from min to max
};
struct Normal {
  double mean = 0;
  double std = 0;
  // Not in the seed's table, accepted as an extension: a sample outside [min, max] is
  // drawn again (a truncated normal), so a speed can never come out negative.
  std::optional<double> min;
  std::optional<double> max;
};
struct Choice {
  std::vector<nlohmann::json> choices;
};
using Distribution = std::variant<Constant, Uniform, Normal, Choice>;

struct ParameterSpec {
  std::string group;  // "ego_vehicle"
  std::string name;   // "initial_speed"; the template refers to it as ${ego_vehicle.initial_speed}
  ValueType type = ValueType::Float;
  std::string unit;
  std::string description;
  Distribution distribution;
  SourceLocation where;
  [[nodiscard]] std::string key() const { return group + "." + name; }
};

// Run settings a logical scenario may suggest for its parameter sets (the `sumo_config`
// of the parameter file takes them, unless `orchestrator sample` options override them).
struct SumoConfigDefaults {
  std::optional<double> step;
  std::optional<double> max_time;
  std::optional<std::string> traffic;
  std::optional<std::string> backend;
};

struct LogicalScenario {
  std::filesystem::path file;
  std::string uuid;
  std::string parent_abstract_uuid;  // "" when it has no abstract scenario
  std::string name;
  std::string description;
  std::string created_at;
  std::vector<ParameterSpec> parameters;  // ordered by group, then name
  std::filesystem::path template_file;    // resolved against the logical file's folder
  SourceLocation template_where;
  SumoConfigDefaults sumo_config;

  [[nodiscard]] const ParameterSpec* find(const std::string& key) const;
  [[nodiscard]] std::vector<std::string> keys() const;
  // logical_{uuid}_parameters.json beside the logical file.
  [[nodiscard]] std::filesystem::path parameter_file() const;
};

// True when the document looks like a logical scenario (has "parameter_space").
bool is_logical_scenario(const JsonDocument& doc);

// Throws ScenarioError listing every problem: unknown distributions and keys (with "did you
// mean"), missing fields, a type that does not fit its distribution, min > max, ...
LogicalScenario load_logical_scenario(const std::filesystem::path& file);
LogicalScenario read_logical_scenario(const JsonDocument& doc);

}  // namespace orch::batch
