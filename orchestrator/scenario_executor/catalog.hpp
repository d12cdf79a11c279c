#pragma once
// The models a scenario may name (model_id), with the dimensions the simulation and the
// collision test use. The default catalog is compiled in (catalog/models.json); a user
// catalog can replace it with --catalog FILE.
#include <string>
#include <string_view>
#include <vector>

#include "sim/actor.hpp"

namespace orch {

class Catalog {
 public:
  // The compiled-in catalog, parsed once; references to its models stay valid.
  static const Catalog& embedded();
  // Throws ScenarioError naming file, line and pointer on a malformed catalog.
  static Catalog load(const std::string& path);
  static Catalog parse(const std::string& text, const std::string& path_for_messages);

  // Exact ids win over patterns; nullptr when unknown.
  [[nodiscard]] const ModelInfo* find(std::string_view model_id) const;
  [[nodiscard]] std::vector<std::string> ids() const;

 private:
  std::vector<ModelInfo> models_;
};

}  // namespace orch
