#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/element_reader.hpp"
#include "openscenario/expression.hpp"
#include "openscenario/variation.hpp"
#include "openscenario/xosc_reader.hpp"

namespace orch::openscenario {
namespace fs = std::filesystem;

namespace {

// A DistributionRange of more values than this is certainly a mistake (a step far too small).
constexpr double kMaxRangeValues = 1e6;

ValueRange read_range(Element& range) {
  ValueRange r{range.number("lowerLimit"), range.number("upperLimit")};
  if (r.lower > r.upper)
    range.fail_attribute("upperLimit", fmt::format("upperLimit {} is below lowerLimit {}", format_number(r.upper),
                                                    format_number(r.lower)));
  range.finish();
  return r;
}

std::optional<ValueRange> read_optional_range(Element& e) {
  auto range = e.optional_child("Range");
  if (!range) return std::nullopt;
  return read_range(*range);
}

double positive_weight(Element& e) {
  const double w = e.number("weight");
  if (!(w > 0)) e.fail_attribute("weight", fmt::format("a weight must be > 0, found {}", format_number(w)));
  return w;
}

double non_negative(Element& e, const char* attribute) {
  const double v = e.number(attribute);
  if (v < 0) e.fail_attribute(attribute, fmt::format("must be >= 0, found {}", format_number(v)));
  return v;
}

// Lower, lower + step, ... up to upper (a last value within 1e-9 steps of upper counts).
std::vector<std::string> range_values(Element& range_element) {
  const double step = range_element.number("stepWidth");
  Element range = range_element.child("Range");
  const ValueRange r = read_range(range);
  range_element.finish();
  if (!(step > 0)) range_element.fail_attribute("stepWidth", fmt::format("stepWidth must be > 0, found {}", format_number(step)));
  const double count = std::floor((r.upper - r.lower) / step + 1e-9) + 1;
  if (!(count <= kMaxRangeValues))  // NaN too
    range_element.fail_attribute("stepWidth", fmt::format("the range gives {:.0f} values (more than {:.0f})", count,
                                                         kMaxRangeValues));
  std::vector<std::string> values;
  for (long long i = 0; i < static_cast<long long>(count); ++i) values.push_back(format_number(r.lower + static_cast<double>(i) * step));
  return values;
}

// UserDefinedDistribution: the standard leaves both its content and its `type` to the tool
// that writes it ("user defined"), so no reading of them is sound here: the error names the
// type and the standard distributions that say the same.
[[noreturn]] void user_defined(Element& e, const char* instead) {
  const std::string type = e.optional_text("type").value_or("");
  e.fail(fmt::format("UserDefinedDistribution (type \"{}\") cannot be sampled: the standard leaves its content to the "
                     "tool that defines the type, and the orchestrator defines none; write the distribution as {} "
                     "instead",
                     type, instead));
}

DeterministicFactor read_single(Element& e) {
  DeterministicFactor f;
  f.where = e.place();
  f.parameters.push_back(e.text("parameterName"));
  Element kind = e.one_of({"DistributionSet", "DistributionRange", "UserDefinedDistribution"});
  std::vector<std::string> values;
  if (kind.name() == "DistributionSet") {
    for (Element element : kind.children("Element")) {
      values.push_back(element.text("value"));
      element.finish();
    }
    if (values.empty()) kind.fail("a DistributionSet needs at least one Element");
    kind.finish();
  } else if (kind.name() == "DistributionRange") {
    values = range_values(kind);
  } else {
    user_defined(kind, "a DistributionSet (the values) or a DistributionRange (lower to upper in steps)");
  }
  e.finish();
  for (auto& v : values) f.options.push_back({std::move(v)});
  return f;
}

DeterministicFactor read_multi(Element& e) {
  DeterministicFactor f;
  f.where = e.place();
  Element set_distribution = e.child("ValueSetDistribution");
  e.finish();
  std::vector<Element> sets = set_distribution.children("ParameterValueSet");
  set_distribution.finish();
  if (sets.empty()) set_distribution.fail("a ValueSetDistribution needs at least one ParameterValueSet");
  // A set may assign only some of the distribution's parameters (the standard: "Set of
  // parameter values that have to be assigned for a single concrete scenario"; esmini's
  // cut-in_parameter_set.xosc does): the parameters are every set's, in order of first
  // appearance, and a set that leaves one out runs it at the scenario's default
  // (filled in by fill_scenario_defaults once the scenario is read).
  std::vector<std::vector<std::pair<std::string, std::string>>> assigned;
  for (Element& set : sets) {
    std::vector<std::pair<std::string, std::string>> assignments;
    for (Element a : set.children("ParameterAssignment")) {
      std::string name = a.text("parameterRef");
      for (const auto& [earlier, value] : assignments)
        if (earlier == name) a.fail_attribute("parameterRef", fmt::format("parameter \"{}\" is assigned twice in this ParameterValueSet", name));
      assignments.emplace_back(std::move(name), a.text("value"));
      a.finish();
    }
    set.finish();
    if (assignments.empty()) set.fail("a ParameterValueSet needs at least one ParameterAssignment");
    for (const auto& [name, value] : assignments)
      if (std::find(f.parameters.begin(), f.parameters.end(), name) == f.parameters.end()) f.parameters.push_back(name);
    assigned.push_back(std::move(assignments));
  }
  for (std::size_t i = 0; i < assigned.size(); ++i) {
    std::vector<std::string> option(f.parameters.size());
    for (std::size_t j = 0; j < f.parameters.size(); ++j) {
      const auto given = std::find_if(assigned[i].begin(), assigned[i].end(),
                                      [&](const auto& a) { return a.first == f.parameters[j]; });
      if (given == assigned[i].end()) f.scenario_defaults.emplace_back(i, j);
      else option[j] = given->second;
    }
    f.options.push_back(std::move(option));
  }
  return f;
}

// The values a ParameterValueSet leaves out: the scenario's declared defaults.
void fill_scenario_defaults(Variation& v) {
  for (DeterministicFactor& f : v.factors)
    for (const auto& [option, parameter] : f.scenario_defaults)
      if (const Parameter* p = v.declaration(f.parameters[parameter])) f.options[option][parameter] = p->value;
}

StochasticParameter read_stochastic(Element& e) {
  StochasticParameter p;
  p.where = e.place();
  p.parameter = e.text("parameterName");
  Element kind = e.one_of({"ProbabilityDistributionSet", "NormalDistribution", "LogNormalDistribution",
                           "UniformDistribution", "PoissonDistribution", "Histogram", "UserDefinedDistribution"});
  e.finish();
  const std::string name(kind.name());
  if (name == "UniformDistribution") {
    Element range = kind.child("Range");
    p.distribution = UniformDistribution{read_range(range)};
  } else if (name == "NormalDistribution") {
    p.distribution = NormalDistribution{kind.number("expectedValue"), non_negative(kind, "variance"), read_optional_range(kind)};
  } else if (name == "LogNormalDistribution") {
    LogNormalDistribution d{kind.number("expectedValue"), non_negative(kind, "variance"), read_optional_range(kind)};
    if (!(d.expected_value > 0))
      kind.fail_attribute("expectedValue", "the expected value of a log-normal distribution must be > 0");
    p.distribution = d;
  } else if (name == "PoissonDistribution") {
    PoissonDistribution d{non_negative(kind, "expectedValue"), read_optional_range(kind)};
    if (d.expected_value > 700)  // exp(-700) is the smallest start the inversion can take
      kind.fail_attribute("expectedValue", "expected values above 700 are not supported");
    p.distribution = d;
  } else if (name == "Histogram") {
    HistogramDistribution h;
    for (Element bin : kind.children("Bin")) {
      const double weight = positive_weight(bin);
      Element range = bin.child("Range");
      h.bins.push_back({weight, read_range(range)});
      bin.finish();
    }
    if (h.bins.empty()) kind.fail("a Histogram needs at least one Bin");
    p.distribution = h;
  } else if (name == "ProbabilityDistributionSet") {
    ProbabilityDistributionSet s;
    for (Element element : kind.children("Element")) {
      const std::string value = element.text("value");
      s.elements.push_back({value, positive_weight(element)});
      element.finish();
    }
    if (s.elements.empty()) kind.fail("a ProbabilityDistributionSet needs at least one Element");
    p.distribution = s;
  } else {
    user_defined(kind, "a ProbabilityDistributionSet (values with weights), a Histogram, or a Uniform, Normal, "
                       "LogNormal or Poisson distribution");
  }
  kind.finish();
  return p;
}

bool numeric(const std::string& type) {
  return type == "double" || type == "integer" || type == "unsignedInt" || type == "unsignedShort";
}

// The varied parameters exist in the scenario, are varied once, and their values fit.
void check_against_scenario(const Variation& v, const xml::XmlSource& source) {
  std::vector<std::string> declared;
  for (const Parameter& p : v.declared) declared.push_back(p.name);
  std::set<std::string> seen;
  const auto fail = [&](const Place& at, const std::string& message) {
    throw ScenarioError(SourceLocation{source.file(), at.path, at.line}, message);
  };
  const auto check_name = [&](const std::string& name, const Place& at) -> const Parameter& {
    const Parameter* p = v.declaration(name);
    if (!p)
      fail(at, fmt::format("the scenario {} declares no parameter \"{}\"{}", v.scenario_file, name,
                           did_you_mean(name, declared)));
    if (!seen.insert(name).second) fail(at, fmt::format("parameter \"{}\" is varied twice", name));
    return *p;
  };
  const auto check_value = [&](const Parameter& p, const std::string& value, const Place& at) {
    if (const std::string problem = check_parameter_value(p.type, value); !problem.empty())
      fail(at, fmt::format("value of parameter \"{}\" ({}): {}", p.name, p.type, problem));
  };
  for (const DeterministicFactor& f : v.factors) {
    std::vector<const Parameter*> params;
    for (const auto& name : f.parameters) params.push_back(&check_name(name, f.where));
    for (const auto& option : f.options)
      for (std::size_t j = 0; j < option.size(); ++j) check_value(*params[j], option[j], f.where);
  }
  for (const StochasticParameter& s : v.distributions) {
    const Parameter& p = check_name(s.parameter, s.where);
    if (const auto* set = std::get_if<ProbabilityDistributionSet>(&s.distribution)) {
      for (const auto& e : set->elements) check_value(p, e.value, s.where);
    } else if (!numeric(p.type)) {
      fail(s.where, fmt::format("parameter \"{}\" is a {}: only a ProbabilityDistributionSet can give its values",
                                p.name, p.type));
    }
  }
}

}  // namespace

std::vector<std::string> Variation::parameter_names() const {
  std::vector<std::string> names;
  for (const auto& f : factors) names.insert(names.end(), f.parameters.begin(), f.parameters.end());
  for (const auto& d : distributions) names.push_back(d.parameter);
  return names;
}

const Parameter* Variation::declaration(const std::string& name) const {
  for (const Parameter& p : declared)
    if (p.name == name) return &p;
  return nullptr;
}

bool is_variation_file(const std::string& path) {
  pugi::xml_document doc;
  if (!doc.load_file(path.c_str())) return false;
  const pugi::xml_node root = doc.document_element();
  return std::string_view(root.name()) == "OpenSCENARIO" && root.child("ParameterValueDistribution");
}

Variation load_variation(const std::string& path) {
  const xml::XmlSource source = xml::XmlSource::load(path);
  const ParameterScope no_parameters;
  Element root(source, source.root(), no_parameters);
  if (root.name() != "OpenSCENARIO") root.fail(fmt::format("expected the root element OpenSCENARIO, found {}", root.name()));
  Variation v;
  v.file = path;
  Element header = root.child("FileHeader");
  const int major = header.integer("revMajor");
  v.rev_minor = header.integer("revMinor");
  // The same revisions as the scenario reader (xosc_reader.cpp): a 1.3 variation file of a 1.3
  // scenario is as valid as a 1.2 one (ParameterValueDistribution is unchanged in 1.3).
  if (major != 1)
    header.fail_attribute("revMajor", fmt::format("OpenSCENARIO {}.{} is not supported: this reads 1.0 to 1.3", major, v.rev_minor));
  if (v.rev_minor < 0 || v.rev_minor > 3)
    header.fail_attribute("revMinor", fmt::format("OpenSCENARIO 1.{} is not supported: this reads 1.0 to 1.3", v.rev_minor));
  header.ignore_attributes({"date", "author", "description"});
  header.ignore_children({"License", "Properties"});
  header.finish();
  Element distribution = root.child("ParameterValueDistribution");
  root.finish();

  Element scenario_file = distribution.child("ScenarioFile");
  const std::string file = scenario_file.text("filepath");
  scenario_file.finish();
  const fs::path resolved = fs::path(file).is_absolute() ? fs::path(file) : fs::path(path).parent_path() / file;
  std::error_code ec;
  if (!fs::is_regular_file(resolved, ec))
    scenario_file.fail_attribute("filepath", fmt::format("no scenario file {}", resolved.lexically_normal().string()));
  v.scenario_file = fs::absolute(resolved).lexically_normal().string();

  Element definition = distribution.one_of({"Deterministic", "Stochastic"});
  distribution.finish();
  if (definition.name() == "Deterministic") {
    for (Element e : definition.children("DeterministicSingleParameterDistribution")) v.factors.push_back(read_single(e));
    for (Element e : definition.children("DeterministicMultiParameterDistribution")) v.factors.push_back(read_multi(e));
    // The product's order is the file's order (the two kinds may be interleaved).
    std::stable_sort(v.factors.begin(), v.factors.end(),
                     [](const DeterministicFactor& a, const DeterministicFactor& b) { return a.where.line < b.where.line; });
    if (v.factors.empty()) definition.fail("Deterministic holds no distribution: the product would be empty");
  } else {
    v.stochastic = true;
    v.number_of_test_runs = definition.integer("numberOfTestRuns");
    if (v.number_of_test_runs < 1)
      definition.fail_attribute("numberOfTestRuns", fmt::format("must be >= 1, found {}", v.number_of_test_runs));
    v.random_seed = definition.optional_number("randomSeed").value_or(0.0);
    for (Element e : definition.children("StochasticDistribution")) v.distributions.push_back(read_stochastic(e));
    if (v.distributions.empty()) definition.fail("Stochastic needs at least one StochasticDistribution");
  }
  definition.finish();

  const Scenario scenario = load_scenario(v.scenario_file);
  v.declared = scenario.parameters;
  v.road_file = scenario.road_file;
  fill_scenario_defaults(v);
  check_against_scenario(v, source);
  return v;
}

}  // namespace orch::openscenario
