#pragma once
// The evaluation file's `EgoModel` key: `EgoModel: r157` or
// `EgoModel: {Name: r157, Parameters: {brake_reaction_time: 1.0, ...}}`. Unknown names and
// parameters are errors with "did you mean", at their key path.
#include <optional>

#include "json/object_reader.hpp"
#include "reference_driver/ego_model.hpp"

namespace orch {

// `parent_value` is the mapping `parent` reads.
std::optional<EgoModelChoice> read_ego_model(ObjectReader& parent, const nlohmann::json& parent_value,
                                             const std::string& key);

}  // namespace orch
