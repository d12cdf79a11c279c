// JsonDocument: lines of every value by JSON pointer, duplicate keys, syntax errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "json/json_document.hpp"

using orch::JsonDocument;
using orch::ScenarioError;

namespace {

// The single diagnostic of the ScenarioError `parse` throws.
orch::Diagnostic parse_failure(const std::string& text) {
  try {
    JsonDocument::parse(text, "f.json");
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.diagnostics().error_count(), 1);
    return e.diagnostics().items().at(0);
  }
  ADD_FAILURE() << "no ScenarioError for: " << text;
  return {};
}

}  // namespace

TEST(JsonDocument, LineOfEveryValue) {
  const auto doc = JsonDocument::parse(R"({
  "a": 1,
  "b": {
    "c": [
      10,
      {"d": true},
      [
        "x"
      ]
    ],
    "e": null
  },
  "f": "text"
})",
                                       "f.json");
  EXPECT_EQ(doc.line_of(""), 1);
  EXPECT_EQ(doc.line_of("/a"), 2);
  EXPECT_EQ(doc.line_of("/b"), 3);
  EXPECT_EQ(doc.line_of("/b/c"), 4);
  EXPECT_EQ(doc.line_of("/b/c/0"), 5);
  EXPECT_EQ(doc.line_of("/b/c/1"), 6);
  EXPECT_EQ(doc.line_of("/b/c/1/d"), 6);
  EXPECT_EQ(doc.line_of("/b/c/2"), 7);
  EXPECT_EQ(doc.line_of("/b/c/2/0"), 8);
  EXPECT_EQ(doc.line_of("/b/e"), 11);
  EXPECT_EQ(doc.line_of("/f"), 13);
  EXPECT_EQ(doc.root()["b"]["c"][1]["d"], true);
  EXPECT_EQ(doc.path(), "f.json");
}

TEST(JsonDocument, NumbersAtTheEndOfALineStayOnTheirLine) {
  // The lexer reads one character past a number; here that character is a newline.
  const auto doc = JsonDocument::parse("[\n1\n,\n2.5\n,\n-3e2\n]", "f.json");
  EXPECT_EQ(doc.line_of("/0"), 2);
  EXPECT_EQ(doc.line_of("/1"), 4);
  EXPECT_EQ(doc.line_of("/2"), 6);
}

TEST(JsonDocument, KeyOnOneLineValueOnTheNext) {
  const auto doc = JsonDocument::parse("{\"a\":\n\n  {\"b\": 1}}", "f.json");
  EXPECT_EQ(doc.line_of("/a"), 1);  // a value is located at its key
  EXPECT_EQ(doc.line_of("/a/b"), 3);
}

TEST(JsonDocument, MissingPointersFallBackToTheNearestAncestor) {
  const auto doc = JsonDocument::parse("{\n\"a\": {\n\"b\": 1\n}\n}", "f.json");
  EXPECT_EQ(doc.line_of("/a/zz"), 2);
  EXPECT_EQ(doc.line_of("/a/zz/yy/0"), 2);
  EXPECT_EQ(doc.line_of("/nothing"), 1);
  const auto where = doc.where("/a/b");
  EXPECT_EQ(where.file, "f.json");
  EXPECT_EQ(where.pointer, "/a/b");
  EXPECT_EQ(where.line, 3);
}

TEST(JsonDocument, KeysWithSlashAndTildeAreEscaped) {
  EXPECT_EQ(orch::json_pointer_child("/x", "a/b~c"), "/x/a~1b~0c");
  EXPECT_EQ(orch::json_pointer_child("", std::size_t{3}), "/3");
  const auto doc = JsonDocument::parse("{\n\"a/b\": 1,\n\"c~d\": 2\n}", "f.json");
  EXPECT_EQ(doc.line_of("/a~1b"), 2);
  EXPECT_EQ(doc.line_of("/c~0d"), 3);
}

TEST(JsonDocument, DuplicateKeysAreAnErrorWithTheirLine) {
  const auto d = parse_failure("{\n\"a\": {\n  \"x\": 1,\n  \"y\": 2,\n  \"x\": 3\n}\n}");
  EXPECT_EQ(d.where.pointer, "/a/x");
  EXPECT_EQ(d.where.line, 5);
  EXPECT_EQ(d.where.file, "f.json");
  EXPECT_NE(d.message.find("duplicate key"), std::string::npos);
}

TEST(JsonDocument, TheSameKeyInDifferentObjectsIsFine) {
  const auto doc = JsonDocument::parse(R"([{"id": 1}, {"id": 2}, {"o": {"id": 3}, "id": 4}])", "f.json");
  EXPECT_EQ(doc.root()[2]["id"], 4);
}

TEST(JsonDocument, SyntaxErrorsNameTheirLine) {
  auto d = parse_failure("{\n\"a\": 1,\n\"b\": ,\n}");
  EXPECT_EQ(d.where.line, 3);
  EXPECT_NE(d.message.find("invalid JSON"), std::string::npos);
  d = parse_failure("{\n\"a\": 1\n");
  EXPECT_EQ(d.where.line, 3);
  d = parse_failure("");
  EXPECT_EQ(d.where.line, 1);
  d = parse_failure("{\"a\": 1} trailing");
  EXPECT_EQ(d.where.line, 1);
  // The format document's example lacks a comma between "ego" and "others".
  d = parse_failure("{\n  \"ego\": {}\n  \"others\": []\n}");
  EXPECT_EQ(d.where.line, 3);
}

TEST(JsonDocument, LoadReadsFilesAndReportsUnreadableOnes) {
  const auto dir = std::filesystem::temp_directory_path() / "orch_json_document_test";
  std::filesystem::create_directories(dir);
  const auto path = (dir / "x.json").string();
  std::ofstream(path) << "\xEF\xBB\xBF{\n\"k\": [1]\n}";  // with a UTF-8 byte order mark
  const auto doc = JsonDocument::load(path);
  EXPECT_EQ(doc.path(), path);
  EXPECT_EQ(doc.line_of("/k/0"), 2);
  try {
    JsonDocument::load((dir / "missing.json").string());
    FAIL() << "expected a ScenarioError";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(e.diagnostics().items().at(0).where.file, (dir / "missing.json").string());
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}
