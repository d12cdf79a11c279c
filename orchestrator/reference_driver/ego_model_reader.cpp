#include "reference_driver/ego_model_reader.hpp"

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "reference_driver/r157_parameters.hpp"

namespace orch {

std::optional<EgoModelChoice> read_ego_model(ObjectReader& parent, const nlohmann::json& parent_value,
                                             const std::string& key) {
  if (!parent.has(key)) return std::nullopt;
  EgoModelChoice choice;
  if (!parent_value.at(key).is_object()) {  // a name (anything else gets choice()'s error)
    const auto name = parent.choice(key, ego_model_names(), Need::Optional);
    if (!name) return std::nullopt;
    choice.name = *name;
    return choice;
  }
  const nlohmann::json* object = parent.object(key, Need::Optional);
  if (!object) return std::nullopt;
  ObjectReader m(parent.doc(), *object, parent.child(key), parent.diags(), key);
  choice.name = m.choice("Name", ego_model_names(), Need::Required).value_or("sumo");
  if (const nlohmann::json* params = m.object("Parameters", Need::Optional)) {
    if (!choice.r157()) m.error("Parameters", "only the r157 model has parameters");
    ObjectReader p(parent.doc(), *params, m.child("Parameters"), parent.diags(), "Parameters");
    for (const auto& info : reference_driver::parameter_infos())
      if (const auto v = p.number(info.name, Need::Optional)) {
        const bool may_be_zero = info.name == "wandering_threshold" || info.name == "pedestrian_margin";
        if (*v < 0 || (*v == 0 && !may_be_zero))
          p.error(info.name, fmt::format("\"{}\" must be {}", info.name, may_be_zero ? "0 or more" : "positive"));
        else choice.parameters[info.name] = *v;
      }
    p.finish();
  }
  m.finish();
  return choice;
}

}  // namespace orch
