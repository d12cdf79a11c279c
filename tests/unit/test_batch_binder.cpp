// Template binding: ${group.name} placeholders become values with their JSON type, or text
// inside longer strings; placeholders and parameters must match one to one.
#include <gtest/gtest.h>

#include "batch/logical_scenario.hpp"
#include "batch/template_binder.hpp"
#include "core/errors.hpp"
#include "scenario_executor/loader.hpp"

using namespace orch;
using namespace orch::batch;

namespace {

const std::string kDir = std::string(ORCH_SOURCE_DIR) + "/scenarios/nightly/";

JsonDocument tmpl(const std::string& text) { return JsonDocument::parse(text, "tmpl.json"); }

LogicalScenario logical_with(const std::string& params) {
  return read_logical_scenario(JsonDocument::parse(
      R"({"uuid": "L1", "template": "cut_in.template.json", "parameter_space": {"g": )" + params + "}}",
      kDir + "logical_L1.json"));
}

}  // namespace

TEST(BatchBinder, WholePlaceholderKeepsTheValuesType) {
  const auto out = bind_template(tmpl(R"({"a": "${g.speed}", "b": ["${g.on}", "${g.name}"], "c": {"d": "${g.n}"}})"),
                                 {{"g.speed", 62.5}, {"g.on", true}, {"g.name", "x"}, {"g.n", 3}});
  EXPECT_TRUE(out["a"].is_number_float());
  EXPECT_EQ(out["a"].get<double>(), 62.5);
  EXPECT_EQ(out["b"][0], true);
  EXPECT_EQ(out["b"][1], "x");
  EXPECT_TRUE(out["c"]["d"].is_number_integer());
}

TEST(BatchBinder, EmbeddedPlaceholdersBecomeTextAndDollarDollarIsLiteral) {
  const auto out = bind_template(tmpl(R"({"t": "gap ${g.gap} m at ${g.v} km/h, literal $${g.gap}", "k": "${g.gap}${g.v}"})"),
                                 {{"g.gap", 12.25}, {"g.v", 80}});
  EXPECT_EQ(out["t"], "gap 12.25 m at 80 km/h, literal ${g.gap}");
  EXPECT_EQ(out["k"], "12.2580");  // two placeholders: text, not a number
}

TEST(BatchBinder, KeepsTheTemplatesKeyOrder) {
  const auto out = bind_template(tmpl(R"({"z": 1, "a": "${g.x}", "m": 2})"), {{"g.x", 1}});
  EXPECT_EQ(out.dump(), R"({"z":1,"a":1,"m":2})");
}

TEST(BatchBinder, UnknownPlaceholderIsAnErrorAtTheTemplatesLine) {
  const auto l = logical_with(R"({"speed": {"distribution": "constant", "value": 1}})");
  const auto d = check_template(l, tmpl("{\n\"a\": \"${g.speed}\",\n\"b\": \"${g.sped}\"}"));
  const std::string text = d.format();
  EXPECT_NE(text.find("tmpl.json:3: error: /b: placeholder ${g.sped} names no parameter"), std::string::npos) << text;
  EXPECT_NE(text.find("did you mean \"g.speed\""), std::string::npos) << text;
}

TEST(BatchBinder, UnusedParameterIsAnErrorAtTheLogicalFilesLine) {
  const auto l = logical_with(R"({"speed": {"distribution": "constant", "value": 1},
      "unused": {"distribution": "constant", "value": 2}})");
  const std::string text = check_template(l, tmpl(R"({"a": "${g.speed}"})")).format();
  EXPECT_NE(text.find("logical_L1.json:2: error: /parameter_space/g/unused: parameter \"g.unused\" is used nowhere"),
            std::string::npos)
      << text;
}

TEST(BatchBinder, MalformedPlaceholdersAreErrors) {
  Diagnostics d;
  find_placeholders(tmpl(R"({"a": "${speed}", "b": "${g.x", "c": "${a.b.c}"})"), d);
  EXPECT_EQ(d.error_count(), 3) << d.format();
  EXPECT_NE(d.format().find("unclosed placeholder"), std::string::npos);
  EXPECT_THROW(bind_template(tmpl(R"({"a": "${g.missing}"})"), {{"g.x", 1}}), ScenarioError);
}

TEST(BatchBinder, ShippedTemplatesBindIntoLoadableScenarios) {
  for (const char* name : {"logical_344b1b1a-8831-46a0-a4e1-e7104d3ce4b5.json", "logical_9202dd94-2666-4583-a45c-f8396b848ae9.json"}) {
    const auto l = load_logical_scenario(kDir + name);
    const auto t = JsonDocument::load(l.template_file.string());
    EXPECT_FALSE(check_template(l, t).has_errors()) << check_template(l, t).format();
    std::map<std::string, nlohmann::json> values;
    for (const auto& p : l.parameters) values[p.key()] = p.type == ValueType::Float ? nlohmann::json(7.5) : nlohmann::json(1);
    const auto bound = bind_template(t, values);
    const auto loaded = load_scenario(JsonDocument::parse(bound.dump(2), "bound.json"));
    EXPECT_TRUE(loaded.scenario.has_value()) << name << "\n" << loaded.diagnostics.format();
  }
}
