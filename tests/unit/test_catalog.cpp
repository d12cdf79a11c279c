// The model catalog: the built-in one, lookups with patterns, and errors in user catalogs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "scenario_executor/catalog.hpp"

using namespace orch;

namespace {

// The ScenarioError's diagnostics, or an empty list when `parse` did not throw.
Diagnostics parse_errors(const std::string& text) {
  try {
    Catalog::parse(text, "cat.json");
  } catch (const ScenarioError& e) {
    return e.diagnostics();
  }
  return {};
}

bool has(const Diagnostics& d, const std::string& pointer, int line, const std::string& text) {
  for (const auto& item : d.items())
    if (item.where.pointer == pointer && item.where.line == line && item.where.file == "cat.json" &&
        item.message.find(text) != std::string::npos)
      return true;
  ADD_FAILURE() << "no error at " << pointer << ":" << line << " saying \"" << text << "\" in:\n" << d.format();
  return false;
}

}  // namespace

TEST(Catalog, BuiltInCatalogHasEveryModelOfTheFormatDocument) {
  const Catalog c = Catalog::embedded();
  for (const char* id : {"vehicle.audi.a2", "vehicle.audi.etron", "vehicle.audi.tt", "vehicle.bmw.grandtourer",
                         "vehicle.chevrolet.impala", "vehicle.charger2020.charger2020", "vehicle.garden.gambulancejp",
                         "vehicle.garden.gpolicecarjp", "vehicle.garden.gpumperjp", "vehicle.lincoln2020.mkz2020",
                         "vehicle.mercedesccc.mercedesccc", "vehicle.mini.cooperst", "vehicle.nissan.micra",
                         "vehicle.tesla.model3", "vehicle.toyota.prius", "vehicle.volkswagen.t2",
                         "vehicle.kawasaki.ninja"}) {
    const ModelInfo* m = c.find(id);
    ASSERT_NE(m, nullptr) << id;
    EXPECT_EQ(m->kind, ActorKind::Vehicle) << id;
    EXPECT_GT(m->length, 1.0) << id;
  }
  EXPECT_TRUE(c.find("vehicle.garden.gpolicecarjp")->emergency);
  EXPECT_FALSE(c.find("vehicle.toyota.prius")->emergency);
  EXPECT_DOUBLE_EQ(c.find("vehicle.toyota.prius")->length, 4.51);
  EXPECT_EQ(c.find("static.prop.barrel")->kind, ActorKind::Obstacle);
  EXPECT_EQ(c.find("vehicle.toyota.pruis"), nullptr);
}

TEST(Catalog, PatternsMatchByPrefixAndExactIdsWin) {
  const Catalog c = Catalog::parse(R"({"models": [
    {"id": "walker.*", "kind": "pedestrian", "length": 1, "width": 1, "height": 1},
    {"id": "walker.pedestrian.*", "kind": "pedestrian", "length": 0.4, "width": 0.5, "height": 1.8},
    {"id": "walker.pedestrian.0009", "kind": "obstacle", "length": 2, "width": 2, "height": 2}]})",
                                   "cat.json");
  EXPECT_EQ(c.find("walker.pedestrian.0001")->id, "walker.pedestrian.*");  // longest prefix
  EXPECT_EQ(c.find("walker.child")->id, "walker.*");
  EXPECT_EQ(c.find("walker.pedestrian.0009")->kind, ActorKind::Obstacle);  // exact beats pattern
  EXPECT_EQ(c.find("walker."), nullptr);  // a pattern needs something after its prefix
  EXPECT_EQ(c.find("vehicle.x"), nullptr);
  EXPECT_EQ(c.ids().size(), 3u);
  EXPECT_EQ(c.ids()[0], "walker.*");
}

TEST(Catalog, UserCatalogErrorsNameFileLineAndPointer) {
  const auto d = parse_errors(R"({
"models": [
  {"id": "a", "kind": "vehicel", "length": 1, "width": 1, "height": 1},
  {"id": "b", "kind": "vehicle", "length": -1, "width": 1, "height": 1, "colour": "red"},
  {"id": "c", "kind": "vehicle", "width": 1, "height": 1},
  {"id": "a*b", "kind": "vehicle", "length": 1, "width": 1, "height": 1},
  {"id": "d", "kind": "vehicle", "length": 1, "width": 1, "height": 1, "emergency": "yes"},
  {"id": "e", "kind": "vehicle", "length": 1, "width": 1, "height": 1},
  {"id": "e", "kind": "vehicle", "length": 1, "width": 1, "height": 1},
  3
],
"descripton": "x"
})");
  EXPECT_TRUE(has(d, "/models/0/kind", 3, "did you mean \"vehicle\"?"));
  EXPECT_TRUE(has(d, "/models/1/length", 4, "must be > 0"));
  EXPECT_TRUE(has(d, "/models/1/colour", 4, "unknown key"));
  EXPECT_TRUE(has(d, "/models/2", 5, "needs \"length\""));
  EXPECT_TRUE(has(d, "/models/3/id", 6, "'*' may only end an id"));
  EXPECT_TRUE(has(d, "/models/4/emergency", 7, "must be true or false"));
  EXPECT_TRUE(has(d, "/models/6/id", 9, "appears twice"));
  EXPECT_TRUE(has(d, "/models/7", 10, "expected the model as an object, found a number"));
  EXPECT_TRUE(has(d, "/descripton", 12, "did you mean \"description\"?"));
  EXPECT_EQ(d.error_count(), 9) << d.format();
}

TEST(Catalog, NotACatalogAtAll) {
  EXPECT_TRUE(has(parse_errors("[]"), "", 1, "expected the model catalog as an object"));
  EXPECT_TRUE(has(parse_errors("{\"models\": []}"), "/models", 1, "lists no models"));
  EXPECT_TRUE(has(parse_errors("{\"models\": [}"), "", 1, "invalid JSON"));
}

TEST(Catalog, LoadFromAFile) {
  const auto dir = std::filesystem::temp_directory_path() / "orch_catalog_test";
  std::filesystem::create_directories(dir);
  const auto path = (dir / "models.json").string();
  std::ofstream(path) << R"({"models": [{"id": "my.car", "kind": "vehicle", "length": 4, "width": 2, "height": 1.5}]})";
  const Catalog c = Catalog::load(path);
  ASSERT_NE(c.find("my.car"), nullptr);
  EXPECT_DOUBLE_EQ(c.find("my.car")->width, 2);
  EXPECT_EQ(c.find("my.car")->vclass, "");
  std::ofstream(path) << "{\n\"models\": 1}";
  try {
    Catalog::load(path);
    FAIL() << "expected a ScenarioError";
  } catch (const ScenarioError& e) {
    ASSERT_EQ(e.diagnostics().error_count(), 1);
    EXPECT_EQ(e.diagnostics().items()[0].where.file, path);
    EXPECT_EQ(e.diagnostics().items()[0].where.line, 2);
  }
  EXPECT_THROW(Catalog::load((dir / "missing.json").string()), ScenarioError);
  std::filesystem::remove_all(dir);
}

TEST(Catalog, KindNames) {
  EXPECT_STREQ(to_string(ActorKind::Vehicle), "vehicle");
  EXPECT_STREQ(to_string(ActorKind::Pedestrian), "pedestrian");
  EXPECT_STREQ(to_string(ActorKind::Obstacle), "obstacle");
}
