// release_tree (json/json_document.hpp): a tree emptied leaves first, so that nlohmann's
// destructor has nothing left to flatten into a copy.
#include <gtest/gtest.h>

#include "json/json_document.hpp"

namespace {

TEST(JsonRelease, EmptiesEveryContainerAndKeepsTheRootsType) {
  nlohmann::json tree = nlohmann::json::parse(R"({"a": [1, [2, {"b": [3, 4]}], "x"], "c": {"d": null}, "e": 5})");
  nlohmann::json kept = tree["a"][1];  // a copy is its own tree
  orch::release_tree(tree);
  EXPECT_TRUE(tree.is_object());
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(kept, nlohmann::json::parse(R"([2, {"b": [3, 4]}])"));

  nlohmann::json array = nlohmann::json::array({nlohmann::json::array({1, 2}), 3});
  orch::release_tree(array);
  EXPECT_TRUE(array.is_array());
  EXPECT_TRUE(array.empty());

  nlohmann::json scalar = 7;
  orch::release_tree(scalar);
  EXPECT_EQ(scalar, 7);
}

TEST(JsonRelease, DocumentsStillCopyAndMove) {
  orch::JsonDocument doc = orch::JsonDocument::parse(R"({"k": [1, 2, 3]})", "doc.json");
  orch::JsonDocument copy = doc;
  orch::JsonDocument moved = std::move(doc);
  EXPECT_EQ(copy.root()["k"].size(), 3u);
  EXPECT_EQ(moved.root()["k"].size(), 3u);
  EXPECT_EQ(moved.line_of("/k"), 1);
}

}  // namespace
