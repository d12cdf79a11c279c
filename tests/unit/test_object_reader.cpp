// ObjectReader: required and optional keys, types, enum choices, unknown keys.
#include <gtest/gtest.h>

#include "json/object_reader.hpp"

using namespace orch;

namespace {

struct Fixture {
  JsonDocument doc;
  Diagnostics diags;
  explicit Fixture(const std::string& text) : doc(JsonDocument::parse(text, "o.json")) {}
  ObjectReader reader(const std::string& pointer = "/o") {
    return ObjectReader(doc, doc.root()["o"], pointer, diags, "thing");
  }
  [[nodiscard]] std::string messages() const { return diags.format(); }
};

}  // namespace

TEST(ObjectReader, ReadsEveryTypeAndKnowsWhatIsThere) {
  Fixture f(R"({"o": {"n": 2.5, "i": 3.0, "s": "x", "b": false, "c": "gods_hand", "obj": {}, "arr": [1]}})");
  auto r = f.reader();
  EXPECT_TRUE(r.is_object());
  EXPECT_TRUE(r.has("n"));
  EXPECT_FALSE(r.has("zz"));
  EXPECT_DOUBLE_EQ(r.number("n", Need::Required).value(), 2.5);
  EXPECT_EQ(r.integer("i", Need::Required), std::optional<int>(3));
  EXPECT_EQ(r.string("s", Need::Required), std::optional<std::string>("x"));
  EXPECT_EQ(r.boolean("b", Need::Required), std::optional<bool>(false));
  EXPECT_EQ(r.choice("c", {"specify", "gods_hand"}, Need::Required), std::optional<std::string>("gods_hand"));
  EXPECT_NE(r.object("obj", Need::Required), nullptr);
  EXPECT_EQ(r.array("arr", Need::Required)->size(), 1u);
  EXPECT_FALSE(r.number("absent", Need::Optional).has_value());
  r.finish();
  EXPECT_EQ(f.diags.items().size(), 0u) << f.messages();
  EXPECT_EQ(r.child("a/b"), "/o/a~1b");
}

TEST(ObjectReader, MissingRequiredKeyIsReportedAtTheObject) {
  Fixture f("{\"o\":\n {\"a\": 1}}");
  auto r = f.reader();
  EXPECT_FALSE(r.string("name", Need::Required).has_value());
  ASSERT_EQ(f.diags.error_count(), 1);
  const auto& d = f.diags.items()[0];
  EXPECT_EQ(d.where.pointer, "/o");
  EXPECT_EQ(d.where.line, 1);
  EXPECT_EQ(d.message, "the thing needs \"name\" (a string)");
}

TEST(ObjectReader, WrongTypesNameWhatWasFound) {
  Fixture f("{\"o\": {\n\"n\": \"1\",\n\"i\": 1.5,\n\"b\": 1,\n\"a\": {},\n\"s\": null\n}}");
  auto r = f.reader();
  EXPECT_FALSE(r.number("n", Need::Required));
  EXPECT_FALSE(r.integer("i", Need::Required));
  EXPECT_FALSE(r.boolean("b", Need::Optional));
  EXPECT_EQ(r.array("a", Need::Required), nullptr);
  EXPECT_FALSE(r.string("s", Need::Required));
  const auto& items = f.diags.items();
  ASSERT_EQ(items.size(), 5u) << f.messages();
  EXPECT_EQ(items[0].format(), "o.json:2: error: /o/n: \"n\" must be a number, found a string");
  EXPECT_EQ(items[1].format(), "o.json:3: error: /o/i: \"i\" must be a whole number, found 1.5");
  EXPECT_EQ(items[2].format(), "o.json:4: error: /o/b: \"b\" must be true or false, found a number");
  EXPECT_EQ(items[3].format(), "o.json:5: error: /o/a: \"a\" must be an array, found an object");
  EXPECT_EQ(items[4].format(), "o.json:6: error: /o/s: \"s\" must be a string, found null");
}

TEST(ObjectReader, ChoiceSuggestsTheNearestValue) {
  Fixture f(R"({"o": {"type": "absolut", "mode": "zzzzzz"}})");
  auto r = f.reader();
  EXPECT_FALSE(r.choice("type", {"absolute", "relative"}, Need::Required));
  EXPECT_FALSE(r.choice("mode", {"absolute", "relative"}, Need::Required));
  ASSERT_EQ(f.diags.error_count(), 2);
  EXPECT_EQ(f.diags.items()[0].message,
            "\"type\" is \"absolut\", expected \"absolute\" or \"relative\" (did you mean \"absolute\"?)");
  EXPECT_EQ(f.diags.items()[1].message.find("did you mean"), std::string::npos);
}

TEST(ObjectReader, UnknownKeysAfterFinishWithSuggestionAndTheAllowedList) {
  Fixture f("{\"o\": {\n\"value\": 1,\n\"vlaue\": 2,\n\"extra\": 3,\n\"note\": 4\n}}");
  auto r = f.reader();
  r.number("value", Need::Required);
  r.allow({"note"});
  r.finish();
  ASSERT_EQ(f.diags.error_count(), 2) << f.messages();
  const auto& items = f.diags.items();
  EXPECT_EQ(items[0].where.pointer, "/o/extra");
  EXPECT_EQ(items[0].where.line, 4);
  EXPECT_EQ(items[0].message, "unknown key \"extra\" in the thing; allowed here: \"note\" or \"value\"");
  EXPECT_EQ(items[1].where.pointer, "/o/vlaue");
  EXPECT_EQ(items[1].where.line, 3);
  EXPECT_NE(items[1].message.find("(did you mean \"value\"?)"), std::string::npos);
}

TEST(ObjectReader, ANonObjectIsOneErrorAndNothingElse) {
  Fixture f("{\"o\":\n [1, 2]}");
  auto r = f.reader();
  EXPECT_FALSE(r.is_object());
  EXPECT_FALSE(r.has("a"));
  EXPECT_FALSE(r.number("a", Need::Required));
  EXPECT_EQ(r.object("b", Need::Required), nullptr);
  r.finish();
  ASSERT_EQ(f.diags.error_count(), 1) << f.messages();
  EXPECT_EQ(f.diags.items()[0].format(), "o.json:1: error: /o: expected the thing as an object, found an array");
}

TEST(ObjectReader, WholeNumbersOutOfRangeAreRefused) {
  Fixture f(R"({"o": {"big": 3000000000, "neg": -7, "exp": 1e2}})");
  auto r = f.reader();
  EXPECT_FALSE(r.integer("big", Need::Required));
  EXPECT_EQ(r.integer("neg", Need::Required), std::optional<int>(-7));
  EXPECT_EQ(r.integer("exp", Need::Required), std::optional<int>(100));
  EXPECT_EQ(f.diags.error_count(), 1) << f.messages();
}

TEST(ObjectReader, WarningsAndErrorsAtKeys) {
  Fixture f("{\"o\": {\n\"k\": 1}}");
  auto r = f.reader();
  r.warning("k", "careful");
  r.error("", "whole object");
  EXPECT_EQ(f.diags.warning_count(), 1);
  EXPECT_EQ(f.diags.items()[0].format(), "o.json:2: warning: /o/k: careful");
  EXPECT_EQ(f.diags.items()[1].format(), "o.json:1: error: /o: whole object");
}

TEST(ObjectReader, KeysReportedByTheCallerAreNeitherRepeatedNorListedAsAllowed) {
  Fixture f(R"({"o": {"value": 1, "next_scenes": [1], "valeu": 2}})");
  auto r = f.reader();
  r.number("value", Need::Required);
  r.error("next_scenes", "belongs elsewhere");
  r.already_reported({"next_scenes", "absent_key"});
  r.finish();
  ASSERT_EQ(f.diags.error_count(), 2) << f.messages();
  EXPECT_EQ(f.diags.items()[0].message, "belongs elsewhere");
  EXPECT_EQ(f.diags.items()[1].message,
            "unknown key \"valeu\" in the thing (did you mean \"value\"?); allowed here: \"value\"");
}
