#include "batch/logical_scenario.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "batch/identifiers.hpp"
#include "core/errors.hpp"
#include "json/json_text.hpp"
#include "json/object_reader.hpp"

namespace orch::batch {

namespace {

using nlohmann::json;

const std::vector<std::string> kTypes{"float", "int", "string", "bool"};
const std::vector<std::string> kDistributions{"constant", "uniform", "normal", "choice"};

// Group and parameter names become `${group.name}` placeholders: a dot inside either would
// make the placeholder ambiguous.
bool is_identifier(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front()))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

std::optional<ValueType> type_from_name(const std::string& s) {
  if (s == "float") return ValueType::Float;
  if (s == "int") return ValueType::Int;
  if (s == "string") return ValueType::String;
  if (s == "bool") return ValueType::Bool;
  return std::nullopt;
}

std::optional<ValueType> type_of_value(const json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return ValueType::Int;
  if (v.is_number_float()) return ValueType::Float;
  if (v.is_string()) return ValueType::String;
  if (v.is_boolean()) return ValueType::Bool;
  return std::nullopt;
}

bool fits(ValueType type, const json& v) {
  switch (type) {
    case ValueType::Float: return v.is_number();
    case ValueType::Int: return v.is_number() && std::floor(v.get<double>()) == v.get<double>();
    case ValueType::String: return v.is_string();
    case ValueType::Bool: return v.is_boolean();
  }
  return false;
}

class ParameterReader {
 public:
  ParameterReader(const JsonDocument& doc, Diagnostics& diags) : doc_(doc), diags_(diags) {}

  std::optional<ParameterSpec> read(const std::string& group, const std::string& name, const json& value,
                                    const std::string& pointer) {
    ObjectReader r(doc_, value, pointer, diags_, fmt::format("parameter \"{}.{}\"", group, name));
    if (!r.is_object()) return std::nullopt;
    ParameterSpec spec;
    spec.group = group;
    spec.name = name;
    spec.where = doc_.where(pointer);
    const auto declared = r.choice("type", kTypes, Need::Optional);
    spec.unit = r.string("unit", Need::Optional).value_or("");
    spec.description = r.string("description", Need::Optional).value_or("");
    const auto dist = r.choice("distribution", kDistributions, Need::Required);
    const int errors_before = diags_.error_count();
    std::optional<ValueType> type = declared ? type_from_name(*declared) : std::nullopt;
    if (dist == "constant") {
      read_constant(r, value, spec, type);
    } else if (dist == "uniform" || dist == "normal") {
      if (type && *type != ValueType::Float && *type != ValueType::Int)
        r.error("type", fmt::format("a {} distribution draws numbers: \"type\" must be \"float\" or \"int\"", *dist));
      spec.type = type.value_or(ValueType::Float);
      if (dist == "uniform") read_uniform(r, spec);
      else read_normal(r, spec);
    } else if (dist == "choice") {
      read_choice(r, spec, type);
    }
    r.finish();
    if (!dist || diags_.error_count() > errors_before) return std::nullopt;
    return spec;
  }

 private:
  void read_constant(ObjectReader& r, const json& object, ParameterSpec& spec, std::optional<ValueType> type) {
    const json* v = r.has("value") ? &object.at("value") : nullptr;
    r.allow({"value"});
    if (!v) {
      r.error("", "a constant distribution needs \"value\"");
      return;
    }
    const auto own = type_of_value(*v);
    if (!own) {
      r.error("value", fmt::format("\"value\" must be a number, a string or true/false, found {}", json_type_name(*v)));
      return;
    }
    spec.type = type.value_or(*own);
    if (!fits(spec.type, *v))
      r.error("value", fmt::format("\"value\" {} is not of type \"{}\"", json_text(*v), type_name(spec.type)));
    spec.distribution = Constant{*v};
  }

  void read_uniform(ObjectReader& r, ParameterSpec& spec) {
    const auto lo = r.number("min", Need::Required);
    const auto hi = r.number("max", Need::Required);
    if (!lo || !hi) return;
    if (*lo > *hi) r.error("max", fmt::format("\"max\" {} is below \"min\" {}", *hi, *lo));
    if (spec.type == ValueType::Int && (std::floor(*lo) != *lo || std::floor(*hi) != *hi))
      r.error("min", "an int parameter needs whole-number \"min\" and \"max\"");
    spec.distribution = Uniform{*lo, *hi};
  }

  void read_normal(ObjectReader& r, ParameterSpec& spec) {
    const auto mean = r.number("mean", Need::Required);
    const auto sd = r.number("std", Need::Required);
    const auto lo = r.number("min", Need::Optional);
    const auto hi = r.number("max", Need::Optional);
    if (!mean || !sd) return;
    if (*sd < 0) r.error("std", fmt::format("\"std\" must not be negative, found {}", *sd));
    if (lo && hi && *lo > *hi) r.error("max", fmt::format("\"max\" {} is below \"min\" {}", *hi, *lo));
    spec.distribution = Normal{*mean, *sd, lo, hi};
  }

  void read_choice(ObjectReader& r, ParameterSpec& spec, std::optional<ValueType> type) {
    const json* list = r.array("choices", Need::Required);
    if (!list) return;
    if (list->empty()) {
      r.error("choices", "\"choices\" must list at least one value");
      return;
    }
    Choice choice;
    std::vector<ValueType> kinds;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const auto own = type_of_value((*list)[i]);
      if (!own) {
        diags_.error(doc_.where(json_pointer_child(r.child("choices"), i)),
                     fmt::format("a choice must be a number, a string or true/false, found {}",
                                 json_type_name((*list)[i])));
        continue;
      }
      kinds.push_back(*own);
      choice.choices.push_back((*list)[i]);
    }
    if (!type && !kinds.empty()) {
      // Without a declared type: whole numbers stay int, any fraction among them makes float.
      const bool all_int = std::all_of(kinds.begin(), kinds.end(), [](ValueType k) { return k == ValueType::Int; });
      const bool any_float = std::find(kinds.begin(), kinds.end(), ValueType::Float) != kinds.end();
      type = all_int ? ValueType::Int : any_float ? ValueType::Float : kinds.front();
    }
    spec.type = type.value_or(ValueType::String);
    for (std::size_t i = 0; i < list->size(); ++i)
      if (type_of_value((*list)[i]) && !fits(spec.type, (*list)[i]))
        diags_.error(doc_.where(json_pointer_child(r.child("choices"), i)),
                     fmt::format("choice {} is not of type \"{}\"", json_text((*list)[i]), type_name(spec.type)));
    spec.distribution = std::move(choice);
  }

  const JsonDocument& doc_;
  Diagnostics& diags_;
};

void read_sumo_config(ObjectReader& top, LogicalScenario& out) {
  const json* cfg = top.object("sumo_config", Need::Optional);
  if (!cfg) return;
  ObjectReader r(top.doc(), *cfg, top.child("sumo_config"), top.diags(), "sumo_config");
  out.sumo_config.step = r.number("step", Need::Optional, Quantity::Time);
  out.sumo_config.max_time = r.number("max_time", Need::Optional, Quantity::Time);
  out.sumo_config.traffic = r.string("traffic", Need::Optional);
  out.sumo_config.backend = r.string("backend", Need::Optional);
  if (out.sumo_config.step && (*out.sumo_config.step < 0.001 || *out.sumo_config.step > 1.0))
    r.error("step", fmt::format("\"step\" must lie in [0.001, 1] s, found {}", *out.sumo_config.step));
  if (out.sumo_config.max_time && *out.sumo_config.max_time <= 0)
    r.error("max_time", fmt::format("\"max_time\" must be positive, found {}", *out.sumo_config.max_time));
  r.finish();
}

}  // namespace

const char* type_name(ValueType t) {
  switch (t) {
    case ValueType::Float: return "float";
    case ValueType::Int: return "int";
    case ValueType::String: return "string";
    case ValueType::Bool: return "bool";
  }
  return "float";
}

const ParameterSpec* LogicalScenario::find(const std::string& key) const {
  for (const auto& p : parameters)
    if (p.key() == key) return &p;
  return nullptr;
}

std::vector<std::string> LogicalScenario::keys() const {
  std::vector<std::string> out;
  for (const auto& p : parameters) out.push_back(p.key());
  return out;
}

std::filesystem::path LogicalScenario::parameter_file() const {
  return file.parent_path() / ("logical_" + uuid + "_parameters.json");
}

bool is_logical_scenario(const JsonDocument& doc) {
  return doc.root().is_object() && doc.root().contains("parameter_space");
}

LogicalScenario read_logical_scenario(const JsonDocument& doc) {
  Diagnostics diags;
  LogicalScenario out;
  out.file = doc.path();
  ObjectReader top(doc, doc.root(), "", diags, "logical scenario");
  if (top.is_object()) {
    out.uuid = top.string("uuid", Need::Required).value_or("");
    if (top.has("uuid") && !out.uuid.empty() && !is_file_safe_id(out.uuid))
      top.error("uuid", fmt::format("\"uuid\" \"{}\" cannot name files: use letters, digits, '-' and '_'", out.uuid));
    out.parent_abstract_uuid = top.string("parent_abstract_uuid", Need::Optional).value_or("");
    out.name = top.string("name", Need::Optional).value_or("");
    out.description = top.string("description", Need::Optional).value_or("");
    out.created_at = top.string("created_at", Need::Optional).value_or("");
    if (const auto tmpl = top.string("template", Need::Required)) {
      out.template_file = std::filesystem::path(doc.path()).parent_path() / *tmpl;
      out.template_where = top.where("template");
      if (!std::filesystem::is_regular_file(out.template_file))
        top.error("template", fmt::format("template scenario {} does not exist", out.template_file.string()));
    }
    read_sumo_config(top, out);
    if (const json* space = top.object("parameter_space", Need::Required)) {
      ParameterReader reader(doc, diags);
      for (auto g = space->begin(); g != space->end(); ++g) {
        const std::string gptr = json_pointer_child("/parameter_space", g.key());
        if (!is_identifier(g.key()))
          diags.error(doc.where(gptr), fmt::format("group name \"{}\" must be letters, digits, '_' or '-' (no dots): "
                                                   "it is written ${{{}.name}} in the template", g.key(), g.key()));
        if (!g->is_object()) {
          diags.error(doc.where(gptr), fmt::format("parameter group \"{}\" must be an object of parameters, found {}",
                                                   g.key(), json_type_name(*g)));
          continue;
        }
        for (auto p = g->begin(); p != g->end(); ++p) {
          const std::string pptr = json_pointer_child(gptr, p.key());
          if (!is_identifier(p.key()))
            diags.error(doc.where(pptr), fmt::format("parameter name \"{}\" must be letters, digits, '_' or '-' (no dots)",
                                                     p.key()));
          if (auto spec = reader.read(g.key(), p.key(), *p, pptr)) out.parameters.push_back(std::move(*spec));
        }
      }
      if (out.parameters.empty() && !diags.has_errors())
        diags.error(doc.where("/parameter_space"), "the parameter space defines no parameter");
    }
    top.finish();
  }
  std::sort(out.parameters.begin(), out.parameters.end(),
            [](const ParameterSpec& a, const ParameterSpec& b) { return a.key() < b.key(); });
  if (diags.has_errors()) throw ScenarioError(diags);
  return out;
}

LogicalScenario load_logical_scenario(const std::filesystem::path& file) {
  return read_logical_scenario(JsonDocument::load(file.string()));
}

}  // namespace orch::batch
