// The model catalog: read with the same readers as scenarios, so a user catalog given
// with --catalog gets the same messages (file, line, pointer, "did you mean").
#include "scenario_executor/catalog.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

#include "core/errors.hpp"
#include "json/json_document.hpp"
#include "json/object_reader.hpp"

namespace orch {

namespace embedded {
std::string_view catalog_json();  // generated from catalog/models.json (cmake/embed_file.cmake)
}  // namespace embedded

namespace {

bool is_pattern(std::string_view id) { return !id.empty() && id.back() == '*'; }

std::optional<ModelInfo> read_model(const JsonDocument& doc, const nlohmann::json& value, const std::string& pointer,
                                    Diagnostics& diags) {
  ObjectReader r(doc, value, pointer, diags, "model");
  const int errors_before = diags.error_count();
  ModelInfo m;
  m.id = r.string("id", Need::Required).value_or("");
  const auto kind = r.choice("kind", {"vehicle", "pedestrian", "obstacle"}, Need::Required);
  m.kind = !kind || *kind == "vehicle" ? ActorKind::Vehicle
           : *kind == "pedestrian"     ? ActorKind::Pedestrian
                                       : ActorKind::Obstacle;
  for (auto [key, field] : {std::pair{"length", &m.length}, std::pair{"width", &m.width},
                            std::pair{"height", &m.height}}) {
    const auto size = r.number(key, Need::Required, Quantity::Length);
    if (size && *size <= 0) r.error(key, fmt::format("\"{}\" must be > 0 m, found {}", key, *size));
    *field = size.value_or(0.0);
  }
  m.vclass = r.string("vclass", Need::Optional).value_or("");
  m.gui_shape = r.string("gui_shape", Need::Optional).value_or("");
  m.emergency = r.boolean("emergency", Need::Optional).value_or(false);
  r.finish();
  if (r.has("id") && m.id.empty()) r.error("id", "\"id\" must not be empty");
  if (m.id.find('*') != std::string::npos && !is_pattern(m.id))
    r.error("id", fmt::format("\"{}\": '*' may only end an id (a prefix pattern such as \"walker.pedestrian.*\")", m.id));
  if (diags.error_count() != errors_before) return std::nullopt;
  return m;
}

// Every model of a catalog document; throws ScenarioError listing every problem.
std::vector<ModelInfo> read_catalog(const JsonDocument& doc) {
  Diagnostics diags;
  ObjectReader top(doc, doc.root(), "", diags, "model catalog");
  top.string("description", Need::Optional);
  const auto* models = top.array("models", Need::Required);
  top.finish();
  std::vector<ModelInfo> out;
  if (models) {
    for (std::size_t i = 0; i < models->size(); ++i) {
      const std::string pointer = json_pointer_child("/models", i);
      auto model = read_model(doc, (*models)[i], pointer, diags);
      if (!model) continue;
      if (std::any_of(out.begin(), out.end(), [&](const ModelInfo& m) { return m.id == model->id; })) {
        diags.error(doc.where(json_pointer_child(pointer, "id")),
                    fmt::format("model id \"{}\" appears twice in the catalog", model->id));
        continue;
      }
      out.push_back(std::move(*model));
    }
    if (models->empty()) diags.error(doc.where("/models"), "the catalog lists no models");
  }
  if (diags.has_errors()) throw ScenarioError(diags);
  return out;
}

}  // namespace

Catalog Catalog::parse(const std::string& text, const std::string& path_for_messages) {
  Catalog catalog;
  catalog.models_ = read_catalog(JsonDocument::parse(text, path_for_messages));
  return catalog;
}

Catalog Catalog::load(const std::string& path) {
  Catalog catalog;
  catalog.models_ = read_catalog(JsonDocument::load(path));  // throws ScenarioError when unreadable
  return catalog;
}

const Catalog& Catalog::embedded() {
  // Parsed once; a broken built-in catalog is a build defect that the unit tests catch.
  static const Catalog built_in = parse(std::string(embedded::catalog_json()), "<built-in catalog>");
  return built_in;
}

const ModelInfo* Catalog::find(std::string_view model_id) const {
  for (const auto& m : models_)
    if (!is_pattern(m.id) && m.id == model_id) return &m;
  // Patterns: the longest matching prefix wins ("walker.*" loses to "walker.pedestrian.*").
  const ModelInfo* best = nullptr;
  for (const auto& m : models_) {
    if (!is_pattern(m.id)) continue;
    const std::string_view prefix = std::string_view(m.id).substr(0, m.id.size() - 1);
    if (model_id.size() > prefix.size() && model_id.substr(0, prefix.size()) == prefix &&
        (!best || prefix.size() + 1 > best->id.size()))
      best = &m;
  }
  return best;
}

std::vector<std::string> Catalog::ids() const {
  std::vector<std::string> out;
  out.reserve(models_.size());
  for (const auto& m : models_) out.push_back(m.id);
  return out;
}

}  // namespace orch
