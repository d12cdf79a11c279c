// The libsumo backend is a module the program loads only when a run asks for it
// (adapters/sumo/libsumo_module.hpp): without it, everything that does not run libsumo
// still works, and a libsumo run is an error that says what is missing and what to choose.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include "support/cli_runner.hpp"

using namespace orch::test;

namespace {

// Points the program at another module file (one that does not exist, one of another
// build), for one test.
class WithLibsumoModule {
 public:
  explicit WithLibsumoModule(const std::filesystem::path& module) { ::setenv("ORCH_LIBSUMO_MODULE", module.c_str(), 1); }
  ~WithLibsumoModule() { ::unsetenv("ORCH_LIBSUMO_MODULE"); }
  WithLibsumoModule(const WithLibsumoModule&) = delete;
  WithLibsumoModule& operator=(const WithLibsumoModule&) = delete;
};

}  // namespace

TEST(LibsumoModuleCli, WithoutTheModuleOnlyLibsumoRunsFailAndSaySo) {
  TempDir dir;
  const std::string scenario = source_path("scenarios/alks_obstacle_stop.json");
  const WithLibsumoModule missing(dir / "no-such-module.so");

  const auto validate = run_cli({"validate", scenario});
  EXPECT_EQ(validate.exit_code, 0) << validate.output;

  const auto traci = run_cli({"run", scenario, "--backend", "traci", "--out", (dir / "traci").string(), "-q", "--no-report"});
  EXPECT_EQ(traci.exit_code, 0) << traci.output;
  EXPECT_EQ(read_json(dir / "traci" / "result.json")["verdict"], "success");

  const auto libsumo = run_cli({"run", scenario, "--out", (dir / "libsumo").string(), "-q", "--no-report"});
  EXPECT_EQ(libsumo.exit_code, 2) << libsumo.output;
  const auto result = read_json(dir / "libsumo" / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  const std::string reason = result["reason"];
  EXPECT_NE(reason.find("no-such-module.so"), std::string::npos) << reason;
  EXPECT_NE(reason.find("--backend traci"), std::string::npos) << reason;
}

// A stale module beside a copied program crashed on the first type whose shape had changed;
// now its build stamp differs and the run ends with an error that says so.
TEST(LibsumoModuleCli, AModuleOfAnotherBuildIsRefusedWithAMessage) {
  TempDir dir;
  const WithLibsumoModule other(ORCH_OTHER_BUILD_MODULE);
  const auto r = run_cli({"run", source_path("scenarios/alks_obstacle_stop.json"), "--out", (dir / "out").string(), "-q",
                          "--no-report"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const auto result = read_json(dir / "out" / "result.json");
  EXPECT_EQ(result["verdict"], "error");
  const std::string reason = result["reason"];
  EXPECT_NE(reason.find("belongs to another build of the orchestrator"), std::string::npos) << reason;
  EXPECT_NE(reason.find("0000000000000000 there"), std::string::npos) << reason;
}

TEST(LibsumoModuleCli, TheDefaultBackendLoadsTheModuleBesideTheProgram) {
  TempDir dir;
  const auto r = run_cli({"run", source_path("scenarios/alks_obstacle_stop.json"), "--out", (dir / "out").string(), "-q",
                          "--no-report"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const auto result = read_json(dir / "out" / "result.json");
  EXPECT_EQ(result["backend"], "libsumo");
  EXPECT_EQ(result["verdict"], "success");
}

namespace {

// Sets an environment variable for one test.
class WithEnv {
 public:
  WithEnv(const char* name, const char* value) : name_(name) { ::setenv(name, value, 1); }
  ~WithEnv() { ::unsetenv(name_); }
  WithEnv(const WithEnv&) = delete;
  WithEnv& operator=(const WithEnv&) = delete;

 private:
  const char* name_;
};

// The dynamic loader's own account (LD_DEBUG=files) of loading a library from disk because
// libsumocpp.so needs it.
bool loaded_for_libsumo(const std::string& output, const std::string& soname) {
  return output.find("file=" + soname + " [0];  needed by") != std::string::npos;
}

}  // namespace

// The build's stand-ins for the GUI, video and image libraries libsumocpp.so names
// (cmake/libsumo_stubs.py) take their place in a run (the real ones are not loaded), and the
// run is the same as with the real libraries: trace.csv and metrics.csv byte for byte.
TEST(LibsumoModuleCli, StandInsReplaceSumosGuiLibrariesAndTheRunStaysTheSame) {
  TempDir dir;
  const std::string scenario = source_path("scenarios/openscenario/overtaking.xosc");
  const WithEnv debug("LD_DEBUG", "files");
  const CliResult with_stand_ins = run_cli({"run", scenario, "--out", (dir / "out").string(), "-q", "--no-report"});
  const std::string trace = slurp(dir / "out" / "trace.csv"), metrics = slurp(dir / "out" / "metrics.csv");
  CliResult with_all;
  {
    const WithEnv all("ORCH_LIBSUMO_ALL_LIBRARIES", "1");
    with_all = run_cli({"run", scenario, "--out", (dir / "out").string(), "-q", "--no-report"});
  }
  ASSERT_EQ(with_all.exit_code, 0) << with_all.output.substr(0, 2000);
  ASSERT_EQ(with_stand_ins.exit_code, 0) << with_stand_ins.output.substr(0, 2000);
  for (const std::string soname : {"libavformat.so.59", "libgdal.so.32", "libosg.so.161"}) {
    EXPECT_TRUE(loaded_for_libsumo(with_all.output, soname)) << soname;
    EXPECT_FALSE(loaded_for_libsumo(with_stand_ins.output, soname)) << soname;
  }
  EXPECT_EQ(trace, slurp(dir / "out" / "trace.csv"));
  EXPECT_EQ(metrics, slurp(dir / "out" / "metrics.csv"));
}

// Stand-ins written for another libsumocpp.so (a SUMO that takes other symbols from those
// libraries) do not let the module load; the program then unloads them and loads the real
// libraries, and the run is the same.
TEST(LibsumoModuleCli, StandInsThatNoLongerFitGiveWayToTheRealLibraries) {
  namespace fs = std::filesystem;
  TempDir dir;
  const fs::path bin = fs::path(ORCH_BINARY).parent_path();
  const fs::path module = dir / "module" / "orchestrator-libsumo.so";
  fs::create_directories(module.parent_path());
  fs::copy_file(bin / "orchestrator-libsumo.so", module);
  fs::copy(bin / "libsumo-stubs", module.parent_path() / "libsumo-stubs", fs::copy_options::recursive);
  ASSERT_TRUE(fs::exists(module.parent_path() / "libsumo-stubs" / "libavutil.so.57"));
  fs::copy_file(ORCH_STALE_STAND_IN, module.parent_path() / "libsumo-stubs" / "libavutil.so.57",
                fs::copy_options::overwrite_existing);
  const std::string scenario = source_path("scenarios/openscenario/overtaking.xosc");

  const auto usual = run_cli({"run", scenario, "--out", (dir / "usual").string(), "-q", "--no-report"});
  ASSERT_EQ(usual.exit_code, 0) << usual.output;
  const WithLibsumoModule stale(module);
  const WithEnv debug("LD_DEBUG", "files");
  const auto r = run_cli({"run", scenario, "--out", (dir / "stale").string(), "-q", "--no-report"});
  ASSERT_EQ(r.exit_code, 0) << r.output.substr(0, 2000);
  EXPECT_EQ(read_json(dir / "stale" / "result.json")["verdict"], "success");
  EXPECT_TRUE(loaded_for_libsumo(r.output, "libavformat.so.59"));
  EXPECT_EQ(slurp(dir / "usual" / "trace.csv"), slurp(dir / "stale" / "trace.csv"));
}
