#pragma once
// Evaluation files (docs/evaluation.md "Evaluation files"): driving_log_replayer's versioned
// scenario shape (../shared/seeds/001) with the use case `scenario_executor`, which runs a
// ScenarioExecutor file with its run settings and judges it by criteria.
//
//   ScenarioFormatVersion: 2.0.0          # major 2 (the 2.x.x shape)
//   ScenarioName: ...
//   ScenarioDescription: ...
//   VehicleModel: car.sedan               # the ego's model (optional)
//   LocalMapPath: $HOME/maps              # a folder of map folders (optional)
//   EgoModel: r157 | {Name: r157, Parameters: {...}}   ReferenceRun: true   (optional)
//   Evaluation:
//     UseCaseName: scenario_executor
//     UseCaseFormatVersion: 0.1.0
//     Conditions:
//       Scenario: highway_cut_in.json     # relative to this file
//       Traffic: none | Seed: 42 | Step: 0.05 | MaxTime: 120 | Backend: libsumo   (optional)
//       Criteria: [ {Name, Type, Actor, Metric, Min, Max, Mode, PassRate, Duration,
//                    FromTime, ToTime, FromScene, ToScene, With, Scene}, ... ]
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/diagnostics.hpp"
#include "criteria/criterion.hpp"
#include "json/json_document.hpp"
#include "reference_driver/ego_model.hpp"

namespace orch {

inline constexpr int kScenarioFormatMajor = 2;
inline constexpr const char* kUseCaseName = "scenario_executor";
inline constexpr const char* kUseCaseFormatVersion = "0.1.0";

struct EvaluationFile {
  std::string path;
  std::string format_version;
  std::string name;
  std::string description;
  std::string vehicle_model;  // "" = the scenario's own
  std::string local_map_path;  // expanded; "" = not given
  std::string use_case_version;
  std::string scenario_file;  // resolved against the file's folder
  std::optional<std::string> traffic;
  std::optional<long long> seed;
  std::optional<double> step;
  std::optional<double> max_time;
  std::optional<std::string> backend;
  std::vector<criteria::CriterionSpec> criteria;
  nlohmann::json conditions;  // Conditions as written (result.jsonl's first line)
  std::optional<EgoModelChoice> ego_model;  // EgoModel (docs/reference-driver.md)
  std::optional<bool> reference_run;        // ReferenceRun
};

struct LoadedEvaluation {
  std::optional<EvaluationFile> file;
  Diagnostics diagnostics;
};

// True for the file names run and validate read as evaluation files (.yaml, .yml).
bool is_evaluation_file(const std::filesystem::path& path);
// Every problem is a diagnostic (file, line, key path); never throws for bad input.
LoadedEvaluation load_evaluation(const std::string& path);
LoadedEvaluation read_evaluation(const JsonDocument& doc);
// $NAME and ${NAME} replaced by the environment's value ("" when unset).
std::string expand_variables(const std::string& text);

}  // namespace orch
