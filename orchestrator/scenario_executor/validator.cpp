// check_scenario: a loaded scenario against itself, the catalog and the map's waypoints.
// This file checks the actors; references and the scene graph have their own files.
#include "scenario_executor/validator.hpp"

#include <fmt/format.h>

#include <map>

#include "core/suggest.hpp"
#include "scenario_executor/validator_internal.hpp"

namespace orch {

namespace scenario_checks {

using namespace orch::scenario;

std::string defined_actor_ids(const Scenario& s) {
  std::vector<std::string> ids{std::to_string(s.ego.id)};
  for (const auto& a : s.others) ids.push_back(std::to_string(a.id));
  std::string out;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i > 0) out += (i + 1 == ids.size()) ? " and " : ", ";
    out += ids[i];
  }
  return out;
}

namespace {

void check_model(CheckContext& ctx, const ActorSpec& actor) {
  if (actor.model_id.empty()) return;  // reported by the loader
  const ModelInfo* model = ctx.catalog.find(actor.model_id);
  if (!model) {
    ctx.diags.error(actor.where, fmt::format("model_id \"{}\" is not in the model catalog{}", actor.model_id,
                                             did_you_mean(actor.model_id, ctx.catalog.ids())));
    return;
  }
  if (actor.is_ego && model->kind != ActorKind::Vehicle)
    ctx.diags.error(actor.where, fmt::format("the ego must be a vehicle; model_id \"{}\" is a {}", actor.model_id,
                                             to_string(model->kind)));
}

void check_unique_ids(CheckContext& ctx) {
  std::map<ActorId, const ActorSpec*> seen{{ctx.s.ego.id, &ctx.s.ego}};
  for (const auto& actor : ctx.s.others) {
    auto [it, inserted] = seen.emplace(actor.id, &actor);
    if (inserted) continue;
    const ActorSpec& first = *it->second;
    ctx.diags.error(actor.where,
                    fmt::format("actor_id {} is used twice: {} at line {} has it already", actor.id,
                                first.is_ego ? "the ego" : "the actor", first.where.line));
  }
}

// Every `others` actor starts somewhere: exactly one opening entry each, and no entry for
// an actor that does not exist or for the ego (whose start is opening_scene.ego).
void check_opening_entries(CheckContext& ctx) {
  std::map<ActorId, const OtherOpening*> entries;
  for (const auto& entry : ctx.s.opening.others) {
    if (entry.actor == ctx.s.ego.id) {
      ctx.diags.error(entry.where, fmt::format("actor_id {} is the ego, whose start is given by "
                                               "\"opening_scene\"/\"ego\"; an entry of \"others\" is for the "
                                               "other actors",
                                               entry.actor));
      continue;
    }
    if (!ctx.s.find_actor(entry.actor)) {
      ctx.diags.error(entry.where, fmt::format("actor_id {} is not defined under \"actors\" (defined: {})",
                                               entry.actor, defined_actor_ids(ctx.s)));
      continue;
    }
    auto [it, inserted] = entries.emplace(entry.actor, &entry);
    if (!inserted)
      ctx.diags.error(entry.where, fmt::format("actor {} has a second opening entry; the first is at line {}",
                                               entry.actor, it->second->where.line));
  }
  for (const auto& actor : ctx.s.others) {
    if (entries.count(actor.id) == 0)
      ctx.diags.error(actor.where, fmt::format("actor {} has no entry in \"scenario\"/\"opening_scene\"/\"others\": "
                                               "every actor needs a start position",
                                               actor.id));
  }
}

}  // namespace

void check_actors(CheckContext& ctx) {
  check_model(ctx, ctx.s.ego);
  for (const auto& actor : ctx.s.others) check_model(ctx, actor);
  check_unique_ids(ctx);
  check_opening_entries(ctx);
}

}  // namespace scenario_checks

Diagnostics check_scenario(const scenario::Scenario& s, const WaypointFile& waypoints, const Catalog& catalog,
                           const ValidationOptions& options) {
  Diagnostics diags;
  scenario_checks::CheckContext ctx{s, waypoints, catalog, options, diags};
  scenario_checks::check_actors(ctx);
  scenario_checks::check_opening(ctx);
  scenario_checks::check_start_cycles(ctx);
  scenario_checks::check_scene_contents(ctx);
  scenario_checks::check_scene_graph(ctx);
  return diags;
}

}  // namespace orch
