#include "evaluation/evaluation_file.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <regex>

#include "reference_driver/ego_model_reader.hpp"
#include "core/errors.hpp"
#include "core/suggest.hpp"
#include "evaluation/yaml_tree.hpp"
#include "json/object_reader.hpp"

namespace orch {

namespace {

// "2.1.0" -> 2; nullopt when it is not MAJOR.MINOR.PATCH.
std::optional<int> major_of(const std::string& version) {
  static const std::regex semver(R"(([0-9]+)\.([0-9]+)\.([0-9]+))");
  std::smatch m;
  if (!std::regex_match(version, m, semver)) return std::nullopt;
  return std::stoi(m[1]);
}

std::vector<std::string> names_of_types() {
  std::vector<std::string> out;
  for (const auto& t : criteria::criterion_types()) out.emplace_back(t.name);
  return out;
}
std::vector<std::string> names_of_metrics() {
  std::vector<std::string> out;
  for (auto n : metrics::metric_names()) out.emplace_back(n);
  return out;
}
std::vector<std::string> names_of_modes() { return {"all_of", "any_of", "pass_rate", "duration"}; }

std::optional<criteria::CriterionSpec> read_criterion(ObjectReader& r) {
  criteria::CriterionSpec c;
  const auto name = r.string("Name", Need::Required);
  const auto type = r.choice("Type", names_of_types(), Need::Optional);
  if (type) c.type = *type;
  if (r.has("Type") && !type) {
    // Reported; what the other keys must be depends on the type, so they are not judged.
    r.allow({"Name", "Actor", "Metric", "Min", "Max", "Mode", "PassRate", "Duration", "FromTime", "ToTime",
             "FromScene", "ToScene", "With", "Scene"});
    r.finish();
    return std::nullopt;
  }
  const criteria::CriterionType* kind = criteria::find_criterion_type(c.type);
  if (const auto actor = r.integer("Actor", Need::Optional)) c.actor = *actor;
  if (c.type == "metric") {
    if (const auto metric = r.choice("Metric", names_of_metrics(), Need::Required)) c.metric = *metric;
  }
  c.min = r.number("Min", Need::Optional);
  c.max = r.number("Max", Need::Optional);
  const auto mode = r.choice("Mode", names_of_modes(), Need::Optional);
  const auto pass_rate = r.number("PassRate", Need::Optional);
  const auto duration = r.number("Duration", Need::Optional, Quantity::Time);
  c.mode = mode ? *criteria::parse_mode(*mode)
           : pass_rate ? criteria::Mode::PassRate
           : duration  ? criteria::Mode::Duration
           : kind      ? kind->mode
                       : criteria::Mode::AllOf;
  if (pass_rate) c.pass_rate = *pass_rate;
  if (duration) c.duration = *duration;
  if (c.mode == criteria::Mode::PassRate && !pass_rate) r.error("Mode", "mode pass_rate needs \"PassRate\" (a percentage)");
  if (c.mode == criteria::Mode::Duration && !duration) r.error("Mode", "mode duration needs \"Duration\" (s)");
  if (pass_rate && (*pass_rate < 0 || *pass_rate > 100)) r.error("PassRate", "\"PassRate\" is a percentage, 0 to 100");
  c.from_time = r.number("FromTime", Need::Optional, Quantity::Time);
  c.to_time = r.number("ToTime", Need::Optional, Quantity::Time);
  c.from_scene = r.integer("FromScene", Need::Optional);
  c.to_scene = r.integer("ToScene", Need::Optional);
  c.scene = r.integer("Scene", Need::Optional);
  if (const auto* with = r.array("With", Need::Optional)) {
    for (const auto& w : *with) c.with.push_back(w.is_string() ? w.get<std::string>() : w.dump());
  }
  // The keys each type needs; keys another type uses are errors here, not silently ignored.
  const bool bounded = c.type == "metric" || c.type == "max_speed" || c.type == "standstill";
  if (bounded && !c.min && !c.max) r.error("", fmt::format("a {} criterion needs \"Min\" or \"Max\"", c.type));
  if ((c.type == "max_speed" || c.type == "standstill") && c.min)
    r.error("Min", fmt::format("a {} criterion takes \"Max\" only", c.type));
  if (c.type == "keep_lane" && !c.max) c.max = 0.0;
  if (c.type != "no_collision" && !c.with.empty()) r.error("With", "\"With\" belongs to no_collision criteria");
  if (c.type != "reach_scene" && c.scene) r.error("Scene", "\"Scene\" belongs to reach_scene criteria");
  if ((c.type == "no_collision" || c.type == "reach_scene") && (c.min || c.max))
    r.error(c.min ? "Min" : "Max", fmt::format("a {} criterion has no bounds", c.type));
  r.finish();
  if (!name) return std::nullopt;
  c.name = *name;
  return c;
}

}  // namespace

bool is_evaluation_file(const std::filesystem::path& path) {
  const auto ext = path.extension().string();
  return ext == ".yaml" || ext == ".yml";
}

std::string expand_variables(const std::string& text) {
  static const std::regex var(R"(\$\{([A-Za-z_][A-Za-z0-9_]*)\}|\$([A-Za-z_][A-Za-z0-9_]*))");
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), var);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const auto& m = *it;
    out += text.substr(last, static_cast<std::size_t>(m.position()) - last);
    const std::string name = m[1].matched ? m[1].str() : m[2].str();
    if (const char* v = std::getenv(name.c_str())) out += v;
    last = static_cast<std::size_t>(m.position() + m.length());
  }
  return out + text.substr(last);
}

LoadedEvaluation read_evaluation(const JsonDocument& doc) {
  LoadedEvaluation out;
  Diagnostics& d = out.diagnostics;
  EvaluationFile f;
  f.path = doc.path();
  ObjectReader top(doc, doc.root(), "", d, "evaluation file");
  if (!top.is_object()) return out;
  if (const auto v = top.string("ScenarioFormatVersion", Need::Required)) {
    f.format_version = *v;
    const auto major = major_of(*v);
    if (!major) top.error("ScenarioFormatVersion", fmt::format("\"{}\" is not a version MAJOR.MINOR.PATCH", *v));
    else if (*major != kScenarioFormatMajor)
      top.error("ScenarioFormatVersion", fmt::format("format version {} is not known to this build (it reads {}.x.x)",
                                                      *v, kScenarioFormatMajor));
  }
  f.name = top.string("ScenarioName", Need::Required).value_or("");
  f.description = top.string("ScenarioDescription", Need::Optional).value_or("");
  f.vehicle_model = top.string("VehicleModel", Need::Optional).value_or("");
  if (const auto p = top.string("LocalMapPath", Need::Optional)) f.local_map_path = expand_variables(*p);
  f.ego_model = read_ego_model(top, doc.root(), "EgoModel");
  f.reference_run = top.boolean("ReferenceRun", Need::Optional);
  top.allow({"SensorModel", "VehicleId"});  // driving_log_replayer's keys that do not apply here
  const nlohmann::json* evaluation = top.object("Evaluation", Need::Required);
  top.finish();
  if (evaluation) {
    ObjectReader ev(doc, *evaluation, top.child("Evaluation"), d, "Evaluation");
    ev.choice("UseCaseName", {kUseCaseName}, Need::Required);
    if (const auto v = ev.string("UseCaseFormatVersion", Need::Required)) {
      f.use_case_version = *v;
      // Before 1.0.0 every minor version may change the format (driving_log_replayer's rule).
      static const std::regex known(R"(0\.1\.[0-9]+)");
      if (!std::regex_match(*v, known))
        ev.error("UseCaseFormatVersion", fmt::format("use case format version {} is not known to this build (it reads "
                                                     "0.1.x)", *v));
    }
    const nlohmann::json* conditions = ev.object("Conditions", Need::Required);
    ev.finish();
    if (conditions) {
      f.conditions = *conditions;
      ObjectReader c(doc, *conditions, ev.child("Conditions"), d, "Conditions");
      if (const auto s = c.string("Scenario", Need::Required)) {
        const std::filesystem::path p(expand_variables(*s));
        f.scenario_file = (p.is_absolute() ? p : std::filesystem::path(doc.path()).parent_path() / p).string();
        if (!std::filesystem::is_regular_file(f.scenario_file))
          c.error("Scenario", fmt::format("no scenario file {}", f.scenario_file));
      }
      if (const auto t = c.string("Traffic", Need::Optional)) f.traffic = *t;
      if (const auto s = c.integer("Seed", Need::Optional)) f.seed = *s;
      f.step = c.number("Step", Need::Optional, Quantity::Time);
      if (f.step && (*f.step < 0.001 || *f.step > 1.0)) c.error("Step", "\"Step\" must lie in [0.001, 1] s");
      f.max_time = c.number("MaxTime", Need::Optional, Quantity::Time);
      if (const auto b = c.choice("Backend", {"libsumo", "traci"}, Need::Optional)) f.backend = *b;
      if (const auto* list = c.array("Criteria", Need::Optional)) {
        for (std::size_t i = 0; i < list->size(); ++i) {
          ObjectReader cr(doc, (*list)[i], json_pointer_child(c.child("Criteria"), i), d, "criterion");
          if (!cr.is_object()) continue;
          if (auto spec = read_criterion(cr)) {
            for (const auto& other : f.criteria)
              if (other.name == spec->name) cr.error("Name", fmt::format("criterion name \"{}\" is used twice", spec->name));
            f.criteria.push_back(std::move(*spec));
          }
        }
      }
      c.finish();
    }
  }
  if (!d.has_errors()) out.file = std::move(f);
  return out;
}

LoadedEvaluation load_evaluation(const std::string& path) {
  try {
    return read_evaluation(load_yaml_document(path));
  } catch (const ScenarioError& e) {
    LoadedEvaluation out;
    out.diagnostics = e.diagnostics();
    return out;
  }
}

}  // namespace orch
