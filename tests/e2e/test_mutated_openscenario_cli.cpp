// The property of test_mutated_scenarios_cli.cpp for the other inputs `run` reads:
// OpenSCENARIO files, the OpenDRIVE roads they name, and evaluation files (YAML). Every
// mutant ends in exit 0/1/2 with a written result.json matching it, no internal error, no
// process left behind. Fixed seeds; ORCH_PROPERTY_SEED / ORCH_PROPERTY_RUNS for the soak.
#include <gtest/gtest.h>

#include "e2e/mutated_run_check.hpp"

using namespace orch::test;
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> files_in(const std::vector<std::string>& dirs, const std::string& extension) {
  std::vector<fs::path> files;
  for (const auto& dir : dirs) {
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == extension) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<fs::path> openscenario_files() {
  return files_in({source_path("scenarios/openscenario"), std::string(ORCH_SHARED_DATA_DIR) + "/openscenario"}, ".xosc");
}

// Short runs: the property is about the ending, not the whole story.
const std::vector<std::string> kRunOptions = {"--max-time", "5"};

}  // namespace

TEST(MutatedOpenScenarioCli, EveryMutatedXoscEndsInAWrittenResult) {
  const auto files = openscenario_files();
  ASSERT_FALSE(files.empty());
  const PropertySeeds p = property_seeds({20261126}, 12);
  SubreaperScope reaper;
  ASSERT_TRUE(reaper.ok());
  TempDir dir;
  for (const std::uint64_t seed : p.seeds) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < p.runs; ++i) {
      const fs::path& source = files[rng() % files.size()];
      pugi::xml_document doc;
      ASSERT_TRUE(doc.load_file(source.c_str())) << source;
      absolutize_paths(doc, source.parent_path());
      const Mutation m = mutate_xml(doc, rng);
      const auto file = dir.write("mutated_" + std::to_string(seed) + "_" + std::to_string(i) + ".xosc", m.text);
      run_mutant_and_check("xosc", seed, i, source, m, file, kRunOptions);
    }
  }
}

TEST(MutatedOpenScenarioCli, EveryMutatedRoadEndsInAWrittenResult) {
  const auto files = openscenario_files();
  ASSERT_FALSE(files.empty());
  // 4164491318: the soak's find (a geometry of negative length, mutant 4 of 16).
  const PropertySeeds p = property_seeds({20261126, 4164491318}, 8);
  SubreaperScope reaper;
  ASSERT_TRUE(reaper.ok());
  TempDir dir;
  for (const std::uint64_t seed : p.seeds) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < p.runs; ++i) {
      const fs::path& source = files[rng() % files.size()];
      pugi::xml_document scenario;
      ASSERT_TRUE(scenario.load_file(source.c_str())) << source;
      absolutize_paths(scenario, source.parent_path());
      pugi::xml_attribute road_attribute = road_file_attribute(scenario);
      ASSERT_TRUE(road_attribute) << source << ": no road network file found";
      const fs::path road = road_attribute.value();
      pugi::xml_document doc;
      ASSERT_TRUE(doc.load_file(road.c_str())) << road;
      const Mutation m = mutate_xml(doc, rng);
      const std::string stem = "mutated_" + std::to_string(seed) + "_" + std::to_string(i);
      const auto road_file = dir.write(stem + ".xodr", m.text);
      road_attribute.set_value(road_file.c_str());
      const auto file = dir.write(stem + ".xosc", xml_text(scenario));
      run_mutant_and_check("xodr", seed, i, road, m, file, kRunOptions);
    }
  }
}

TEST(MutatedOpenScenarioCli, EveryMutatedEvaluationFileEndsInAWrittenResult) {
  const auto files = files_in({source_path("scenarios/evaluation")}, ".yaml");
  ASSERT_FALSE(files.empty());
  // 2679876088: the soak's find (bytes that are not UTF-8 in a string, mutant 7 of 16).
  const PropertySeeds p = property_seeds({20261126, 2679876088}, 8);
  SubreaperScope reaper;
  ASSERT_TRUE(reaper.ok());
  TempDir dir;
  for (const std::uint64_t seed : p.seeds) {
    std::mt19937_64 rng(seed);
    for (int i = 0; i < p.runs; ++i) {
      const fs::path& source = files[rng() % files.size()];
      const Mutation m = mutate_yaml(slurp(source), source.parent_path(), rng);
      const auto file = dir.write("mutated_" + std::to_string(seed) + "_" + std::to_string(i) + ".yaml", m.text);
      run_mutant_and_check("yaml", seed, i, source, m, file, {"--max-time", "10"});
    }
  }
}

// Values no map can hold are refused at `validate`, naming the attribute and its line: a
// lane position 1e300 m along the road, and a road 1e300 m long.
TEST(MutatedOpenScenarioCli, ImplausibleValuesAreRefusedNamingTheAttribute) {
  const fs::path source = source_path("scenarios/openscenario/cut_in_traffic.xosc");
  TempDir dir;
  {
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(source.c_str()));
    absolutize_paths(doc, source.parent_path());
    pugi::xml_node lane = doc.select_node("//LanePosition").node();
    ASSERT_TRUE(lane);
    lane.attribute("s").set_value("1e300");
    const auto file = dir.write("far.xosc", xml_text(doc));
    const auto v = run_cli({"validate", file.string()});
    EXPECT_EQ(v.exit_code, 1) << v.output;
    EXPECT_NE(v.output.find("s is 1e+300 m: its magnitude is beyond 10,000 km"), std::string::npos) << v.output;
    TempDir out;
    const auto r = run_scenario(file.string(), out, kRunOptions);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_TRUE(fs::exists(out / "result.json"));
  }
  {
    pugi::xml_document scenario;
    ASSERT_TRUE(scenario.load_file(source.c_str()));
    absolutize_paths(scenario, source.parent_path());
    pugi::xml_attribute road_attribute = road_file_attribute(scenario);
    pugi::xml_document road;
    ASSERT_TRUE(road.load_file(road_attribute.value()));
    road.select_node("//road").node().attribute("length").set_value("1e300");
    road_attribute.set_value(dir.write("long.xodr", xml_text(road)).c_str());
    const auto file = dir.write("long.xosc", xml_text(scenario));
    const auto v = run_cli({"validate", file.string()});
    EXPECT_EQ(v.exit_code, 1) << v.output;
    EXPECT_NE(v.output.find("length is 1e+300 m"), std::string::npos) << v.output;
  }
}
