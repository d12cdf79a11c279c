#pragma once
// What a run takes from an evaluation file (docs/evaluation.md) besides the scenario and its
// run settings: the criteria, the ego's model, and how result.jsonl is written.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "criteria/criterion.hpp"

namespace orch {

struct EvaluationRequest {
  std::string file;  // the evaluation file, for result.json's inputs
  std::vector<criteria::CriterionSpec> criteria;
  nlohmann::json conditions;    // as written: result.jsonl's first line
  std::string vehicle_model;    // the ego's model id ("" = the scenario's)
  int jsonl_every = 1;          // a result.jsonl frame line every N steps
};

}  // namespace orch
