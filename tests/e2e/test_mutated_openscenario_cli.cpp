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

pugi::xml_document load_xml(const fs::path& path) {
  pugi::xml_document doc;
  if (!doc.load_file(path.c_str())) throw std::runtime_error("cannot read " + path.string());
  return doc;
}

std::filesystem::path write_file(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

TEST(MutatedOpenScenarioCli, EveryMutatedXoscEndsInAWrittenResult) {
  check_mutants("xosc", openscenario_files(), property_seeds({20261126}, 12), kRunOptions,
                [](const fs::path& source, std::mt19937_64& rng, const std::string& stem) {
                  pugi::xml_document doc = load_xml(source);
                  absolutize_paths(doc, source.parent_path());
                  Mutation m = mutate_xml(doc, rng);
                  const auto file = write_file(stem + ".xosc", m.text);
                  return WrittenMutant{std::move(m), file, source};
                });
}

TEST(MutatedOpenScenarioCli, EveryMutatedRoadEndsInAWrittenResult) {
  // 4164491318: the soak's find (a geometry of negative length, mutant 4 of 16).
  check_mutants("xodr", openscenario_files(), property_seeds({20261126, 4164491318}, 8), kRunOptions,
                [](const fs::path& source, std::mt19937_64& rng, const std::string& stem) {
                  pugi::xml_document scenario = load_xml(source);
                  absolutize_paths(scenario, source.parent_path());
                  pugi::xml_attribute road_attribute = road_file_attribute(scenario);
                  if (!road_attribute) throw std::runtime_error(source.string() + ": no road network file found");
                  const fs::path road = road_attribute.value();
                  pugi::xml_document doc = load_xml(road);
                  Mutation m = mutate_xml(doc, rng);
                  road_attribute.set_value(write_file(stem + ".xodr", m.text).c_str());
                  const auto file = write_file(stem + ".xosc", xml_text(scenario));
                  return WrittenMutant{std::move(m), file, road};
                });
}

TEST(MutatedOpenScenarioCli, EveryMutatedEvaluationFileEndsInAWrittenResult) {
  // 2679876088: the soak's find (bytes that are not UTF-8 in a string, mutant 7 of 16).
  check_mutants("yaml", files_in({source_path("scenarios/evaluation")}, ".yaml"),
                property_seeds({20261126, 2679876088}, 8), {"--max-time", "10"},
                [](const fs::path& source, std::mt19937_64& rng, const std::string& stem) {
                  Mutation m = mutate_yaml(slurp(source), source.parent_path(), rng);
                  const auto file = write_file(stem + ".yaml", m.text);
                  return WrittenMutant{std::move(m), file, source};
                });
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
    // The soak's third find (seed 3406330881): a box centre 1.4 km from the reference point
    // crashed libsumo. Checked on its own file below.
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
    pugi::xml_document doc = load_xml(source);
    absolutize_paths(doc, source.parent_path());
    doc.select_node("//BoundingBox/Center").node().attribute("x").set_value("1400000");
    const auto file = dir.write("box.xosc", xml_text(doc));
    const auto v = run_cli({"validate", file.string()});
    EXPECT_EQ(v.exit_code, 1) << v.output;
    EXPECT_NE(v.output.find("x 1400000 m: a bounding box's centre is at most 1000 m"), std::string::npos) << v.output;
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
