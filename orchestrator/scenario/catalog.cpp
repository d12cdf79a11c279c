// TEMPORARY placeholder (being written this session).
#include "scenario/catalog.hpp"
namespace orch {
const char* to_string(ActorKind k) { return k == ActorKind::Vehicle ? "vehicle" : k == ActorKind::Pedestrian ? "pedestrian" : "obstacle"; }
Catalog Catalog::embedded() { return {}; }
Catalog Catalog::load(const std::string&) { return {}; }
const ModelInfo* Catalog::find(std::string_view) const { return nullptr; }
}
