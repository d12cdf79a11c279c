// JsonDocument's cost is bounded by the input: nesting deeper than kMaxJsonDepth is an
// error naming its line, and the line index keeps no pointer string per value, so that
// deep (but allowed) documents and long arrays are indexed and asked in linear time.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "json/json_document.hpp"

using orch::JsonDocument;
using orch::ScenarioError;

namespace {

std::string nested_arrays(std::size_t depth, const std::string& between = "") {
  return std::string(depth, '[') + between + std::string(depth, ']');
}

orch::Diagnostic failure_of(const std::string& text) {
  try {
    JsonDocument::parse(text, "deep.json");
  } catch (const ScenarioError& e) {
    return e.diagnostics().items().at(0);
  }
  ADD_FAILURE() << "no ScenarioError";
  return {};
}

}  // namespace

TEST(JsonLimits, NestingDeeperThanTheLimitIsAnErrorNamingItsLine) {
  // The limit's depth is read; one more level is refused on the line where it opens.
  EXPECT_NO_THROW(JsonDocument::parse(nested_arrays(orch::kMaxJsonDepth), "deep.json"));
  const std::string text = "{\n\"a\":\n" + std::string(orch::kMaxJsonDepth - 1, '[') + "\n[[]" +
                           std::string(orch::kMaxJsonDepth, ']') + "}";
  const auto d = failure_of(text);
  EXPECT_EQ(d.where.file, "deep.json");
  EXPECT_EQ(d.where.line, 4);
  EXPECT_NE(d.message.find("nested more than 256 deep"), std::string::npos) << d.message;
}

TEST(JsonLimits, BracketsInsideStringsDoNotCount) {
  const std::string brackets(5000, '[');
  const auto doc = JsonDocument::parse("{\"s\": \"" + brackets + "\\\"" + brackets + "\"}", "s.json");
  EXPECT_EQ(doc.root()["s"].get<std::string>().size(), 10001u);
}

TEST(JsonLimits, AMillionBytesOfNestingFailsAtOnce) {
  // 500,000 levels: the old line pass kept a pointer per level (quadratic: about 250 GB).
  const auto d = failure_of(nested_arrays(500000));
  EXPECT_EQ(d.where.line, 1);
  const auto objects = failure_of(std::string(100000, '{'));  // never closed either
  EXPECT_NE(objects.message.find("nested"), std::string::npos) << objects.message;
}

TEST(JsonLimits, LinesOfDeepAndWideDocuments) {
  // Depth at the limit, one value per line, and a long array: every line is found.
  std::string text;
  for (std::size_t i = 0; i < orch::kMaxJsonDepth - 1; ++i) text += "{\"k~/\":\n";
  text += "[\n";
  for (int i = 0; i < 20000; ++i) text += std::to_string(i) + (i + 1 < 20000 ? ",\n" : "\n");
  text += "]";
  for (std::size_t i = 0; i < orch::kMaxJsonDepth - 1; ++i) text += "}";
  const auto doc = JsonDocument::parse(text, "wide.json");
  std::string pointer;
  for (std::size_t i = 0; i < orch::kMaxJsonDepth - 1; ++i) pointer += "/k~0~1";
  const int array_line = static_cast<int>(orch::kMaxJsonDepth) - 1;  // the key of the last object
  EXPECT_EQ(doc.line_of(pointer), array_line);
  EXPECT_EQ(doc.line_of(pointer + "/0"), array_line + 2);
  EXPECT_EQ(doc.line_of(pointer + "/19999"), array_line + 20001);
  EXPECT_EQ(doc.line_of(pointer + "/20000"), array_line);  // no such item: the array's line
  EXPECT_EQ(doc.line_of(pointer + "/01"), array_line);     // not an index (RFC 6901)
  EXPECT_EQ(doc.line_of("/k~0~1/k~0~1/nothing/else"), 2);
  EXPECT_EQ(doc.line_of("/k/"), 1);
}

TEST(JsonLimits, ADuplicateKeyDeepInArraysNamesItsPointer) {
  const auto d = failure_of("{\"a\": [1, {\"b\": [[], {\"c\": 1,\n\"c\": 2}]}]}");
  EXPECT_EQ(d.where.pointer, "/a/1/b/1/c");
  EXPECT_EQ(d.where.line, 2);
}

TEST(JsonLimits, FoldersAndMissingFilesAreNamedErrors) {
  const auto dir = failure_of("");  // empty text: a syntax error on line 1
  EXPECT_EQ(dir.where.line, 1);
  try {
    JsonDocument::load(ORCH_SOURCE_DIR);
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
  try {
    JsonDocument::load("/nonexistent/x.json");
    FAIL();
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.json: error: /: cannot open file for reading (No such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(JsonLimits, ANumberBeyondDoubleIsASyntaxErrorWithItsLine) {
  // nlohmann throws out_of_range (no position) for it, not parse_error.
  const auto d = failure_of("{\n\"a\": 1,\n\"b\": -1e400\n}");
  EXPECT_EQ(d.where.line, 3);
  EXPECT_NE(d.message.find("invalid JSON"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("1e400"), std::string::npos) << d.message;
}
