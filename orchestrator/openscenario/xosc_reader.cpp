#include "openscenario/xosc_reader.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/reader_context.hpp"
#include "openscenario/rule.hpp"
#include "openscenario/text_number.hpp"

namespace orch::openscenario {
namespace fs = std::filesystem;
using reading::Context;

namespace {

void read_header(Element& root, Scenario& scenario) {
  Element header = root.child("FileHeader");
  scenario.rev_major = header.integer("revMajor");
  scenario.rev_minor = header.integer("revMinor");
  if (scenario.rev_major != 1)
    header.fail_attribute("revMajor", fmt::format("OpenSCENARIO {}.{} is not supported: this reads 1.0 to 1.3",
                                                  scenario.rev_major, scenario.rev_minor));
  if (scenario.rev_minor < 0 || scenario.rev_minor > 3)
    header.fail_attribute("revMinor", fmt::format("OpenSCENARIO 1.{} is not supported: this reads 1.0 to 1.3",
                                                  scenario.rev_minor));
  scenario.description = header.optional_text("description").value_or("");
  header.ignore_attributes({"date", "author"});
  header.ignore_children({"License", "Properties"});
  header.finish();
}

bool holds(Rule rule, const std::string& type, const std::string& value, const std::string& bound, Element& at) {
  if (type == "string" || type == "boolean" || type == "dateTime") return satisfies(rule, value, bound);
  const auto b = parse_whole<double>(bound);
  if (!b) at.fail_attribute("value", fmt::format("expected a number, found \"{}\"", bound));
  return satisfies(rule, parse_whole<double>(value).value_or(0.0), *b);
}

// Declarations in order, then the overrides, then every ConstraintGroup (OR of ANDs) on the
// final values: a constraint may use other parameters.
std::vector<Parameter> read_parameters(Element& root, const LoadOptions& options, Context& context) {
  ParameterScope& scope = context.global;
  std::vector<Parameter> parameters;
  std::vector<int> lines;  // of `parameters`' declarations
  auto declarations = root.optional_child("ParameterDeclarations");
  std::vector<Element> elements = declarations ? declarations->children("ParameterDeclaration") : std::vector<Element>{};
  if (declarations) declarations->finish();
  for (Element& d : elements) {
    Parameter p = reading::read_declaration(d);
    const auto earlier = std::find_if(parameters.begin(), parameters.end(), [&](const Parameter& o) { return o.name == p.name; });
    if (earlier != parameters.end()) {
      // A parameter is named by its name in its scope: a second declaration that says the same
      // changes nothing (esmini's follow_reference.xosc repeats one), one that differs is ambiguous.
      const int line = lines[static_cast<std::size_t>(earlier - parameters.begin())];
      if (earlier->type != p.type || earlier->value != p.value)
        d.fail_attribute("name", fmt::format("parameter \"{}\" is declared twice, differently (first at line {})",
                                             p.name, line));
      context.warnings.warning(d.source().where(d.node(), "name"),
                               fmt::format("parameter \"{}\" is declared a second time, as at line {}", p.name, line));
      continue;
    }
    scope.set(p.name, p.type, p.value, p.name);
    parameters.push_back(p);
    lines.push_back(d.place().line);
  }
  std::vector<std::string> names;
  for (const Parameter& p : parameters) names.push_back(p.name);
  for (const auto& [name, value] : options.parameter_overrides) {
    auto it = std::find_if(parameters.begin(), parameters.end(), [&](const Parameter& p) { return p.name == name; });
    if (it == parameters.end())
      throw ScenarioError(SourceLocation{"--param", name, 0},
                          fmt::format("the scenario declares no parameter \"{}\"{}", name, did_you_mean(name, names)));
    const std::string problem = check_parameter_value(it->type, value);
    if (!problem.empty())
      throw ScenarioError(SourceLocation{"--param", name, 0}, fmt::format("{} ({} parameter)", problem, it->type));
    it->value = value;
    it->overridden = true;
    scope.assign(name, value);
  }
  for (std::size_t i = 0; i < elements.size(); ++i) {
    Element& d = elements[i];
    const Parameter& p = parameters[i];
    std::vector<Element> groups = d.children("ConstraintGroup");
    d.finish();
    if (groups.empty()) continue;
    bool any = false;
    std::string violated;
    for (Element& group : groups) {
      bool all = true;
      for (Element c : group.children("ValueConstraint")) {
        const Rule rule = reading::read_rule(c);
        const std::string bound = c.text("value");
        if (!holds(rule, p.type, p.value, bound, c)) {
          all = false;
          if (violated.empty()) violated = fmt::format("{} {}", c.node().attribute("rule").value(), bound);
        }
        c.finish();
      }
      group.finish();
      any = any || all;
    }
    if (!any)
      throw ScenarioError(d.source().where(d.node(), "value"),
                          fmt::format("parameter \"{}\" = {} violates its constraints ({}{})", p.name, p.value,
                                      violated, p.overridden ? ", value given by --param" : ""));
  }
  return parameters;
}

// Every trailer an entity tows from the start is another entity, towed by no other.
void check_trailers(const Scenario& scenario, const std::vector<std::pair<std::string, Place>>& tractors) {
  std::vector<std::string> names;
  for (const Entity& e : scenario.entities) names.push_back(e.name);
  std::map<std::string, std::string> towed_by;
  for (const auto& [tractor, place] : tractors) {
    const std::string& trailer = scenario.entity(tractor)->trailer;
    const SourceLocation where{scenario.file, place.path + "/Trailer", place.line};
    if (scenario.entity(trailer) == nullptr)
      throw ScenarioError(where, fmt::format("the trailer of \"{}\" is no entity: \"{}\"{}", tractor, trailer,
                                             did_you_mean(trailer, names)));
    if (trailer == tractor) throw ScenarioError(where, fmt::format("\"{}\" cannot tow itself", tractor));
    if (!towed_by.emplace(trailer, tractor).second)
      throw ScenarioError(where, fmt::format("\"{}\" is the trailer of both \"{}\" and \"{}\"", trailer,
                                             towed_by[trailer], tractor));
  }
}

// An ActivateControllerAction's objectControllerRef (1.3) names one of each actor's ObjectControllers.
void check_controller_ref(const Scenario& scenario, const PrivateAction& action, const std::string& entity,
                          const Place& place) {
  const auto* activate = std::get_if<ActivateControllerAction>(&action);
  const Entity* e = scenario.entity(entity);
  if (activate == nullptr || activate->object_controller.empty() || e == nullptr) return;
  std::vector<std::string> names;
  for (const auto& [name, controller] : e->object_controllers) {
    if (name == activate->object_controller) return;
    names.push_back(name);
  }
  throw ScenarioError(SourceLocation{scenario.file, place.path, place.line},
                      fmt::format("objectControllerRef \"{}\": entity {} has no ObjectController of that name{}",
                                  activate->object_controller, entity,
                                  names.empty() ? " (it has none)" : did_you_mean(activate->object_controller, names)));
}

void check_controller_refs(const Scenario& scenario) {
  for (const InitAction& a : scenario.storyboard.init) check_controller_ref(scenario, a.action, a.entity, a.place);
  for (const Story& story : scenario.storyboard.stories)
    for (const Act& act : story.acts)
      for (const ManeuverGroup& g : act.groups)
        for (const Maneuver& m : g.maneuvers)
          for (const Event& ev : m.events)
            for (const Action& a : ev.actions)
              for (const std::string& actor : a.actors) check_controller_ref(scenario, a.action, actor, a.place);
}

// VariableDeclarations (1.2): like parameters, but changed only by VariableActions and read
// only by VariableConditions (a "$name" in an attribute is always a parameter).
std::vector<Parameter> read_variables(Element& root) {
  std::vector<Parameter> variables;
  auto declarations = root.optional_child("VariableDeclarations");
  if (!declarations) return variables;
  for (Element d : declarations->children("VariableDeclaration")) {
    Parameter v = reading::read_declaration(d, "variableType");
    for (const Parameter& other : variables)
      if (other.name == v.name) d.fail_attribute("name", fmt::format("variable \"{}\" is declared twice", v.name));
    variables.push_back(v);
    d.finish();
  }
  declarations->finish();
  return variables;
}

// MonitorDeclarations (1.3): named booleans with their initial values, set by
// SetMonitorActions (the standard's means for a scenario to report whether what it tests held).
std::vector<std::pair<std::string, bool>> read_monitors(Element& root) {
  std::vector<std::pair<std::string, bool>> monitors;
  auto declarations = root.optional_child("MonitorDeclarations");
  if (!declarations) return monitors;
  for (Element d : declarations->children("MonitorDeclaration")) {
    const std::string name = d.text("name");
    for (const auto& other : monitors)
      if (other.first == name) d.fail_attribute("name", fmt::format("monitor \"{}\" is declared twice", name));
    monitors.emplace_back(name, d.boolean("value"));
    d.finish();
  }
  declarations->finish();
  return monitors;
}

}  // namespace

std::map<std::string, std::string> parse_parameter_overrides(const std::vector<std::string>& texts) {
  std::map<std::string, std::string> overrides;
  for (const std::string& text : texts) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0)
      throw OrchError(fmt::format("--param \"{}\": expected NAME=VALUE", text));
    if (!overrides.emplace(text.substr(0, equals), text.substr(equals + 1)).second)
      throw OrchError(fmt::format("--param {} is given twice", text.substr(0, equals)));
  }
  return overrides;
}

Scenario load_scenario(const std::string& path, const LoadOptions& options) {
  const xml::XmlSource source = xml::XmlSource::load(path);
  Context context;
  const reading::ContextInUse in_use(context);
  Element root(source, source.root(), context.global);
  if (root.name() != "OpenSCENARIO")
    root.fail(fmt::format("expected the root element OpenSCENARIO, found {}", root.name()));
  Scenario scenario;
  scenario.file = path;
  read_header(root, scenario);
  if (root.optional_child("ParameterValueDistribution"))
    root.fail("this is a parameter variation file (ParameterValueDistribution), not a scenario; "
              "check it with `orchestrator validate`, run it with `orchestrator batch` or `sample`");
  if (root.optional_child("Catalog")) root.fail("this is a catalog file, not a scenario");
  scenario.parameters = read_parameters(root, options, context);
  scenario.variables = read_variables(root);
  context.variables = scenario.variables;
  scenario.monitors = read_monitors(root);
  for (const auto& monitor : scenario.monitors) context.monitors.push_back(monitor.first);
  const std::string dir = fs::path(path).parent_path().string();
  if (auto locations = root.optional_child("CatalogLocations")) reading::read_catalog_locations(*locations, dir, context);
  Element network = root.child("RoadNetwork");
  if (auto logic = network.optional_child("LogicFile")) {
    const std::string file = logic->text("filepath");
    const fs::path resolved = fs::path(file).is_absolute() ? fs::path(file) : fs::path(dir) / file;
    std::error_code ec;
    if (!fs::is_regular_file(resolved, ec))
      logic->fail_attribute("filepath", fmt::format("no OpenDRIVE file {}", resolved.lexically_normal().string()));
    scenario.road_file = fs::absolute(resolved).lexically_normal().string();
    logic->finish();
  }
  if (auto signals = network.optional_child("TrafficSignals")) {
    scenario.signal_controllers = reading::read_traffic_signals(*signals);
    context.signal_controllers = scenario.signal_controllers;
  }
  network.ignore_children({"SceneGraphFile", "UsedArea"});
  network.finish();
  Element entities = root.child("Entities");
  std::vector<std::pair<std::string, Place>> trailer_places;  // tractor -> where its Trailer is written
  for (Element object : entities.children("ScenarioObject")) {
    for (Entity& entity : reading::read_entity(object, context)) {
      if (scenario.entity(entity.name) != nullptr)
        object.fail(fmt::format("a second entity named \"{}\"", entity.name));
      if (!entity.trailer.empty()) trailer_places.emplace_back(entity.name, object.place());
      scenario.entities.push_back(std::move(entity));
    }
  }
  entities.finish();
  check_trailers(scenario, trailer_places);
  Element storyboard = root.child("Storyboard");
  scenario.storyboard = reading::read_storyboard(storyboard, scenario, context);
  reading::check_traffic_stops(context);
  check_controller_refs(scenario);
  root.finish();
  scenario.local_parameters = context.local_parameters;
  scenario.warnings = context.warnings;
  return scenario;
}

}  // namespace orch::openscenario
