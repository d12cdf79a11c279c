// The libsumo backend is a module the program loads only when a run asks for it
// (adapters/sumo/libsumo_module.hpp): without it, everything that does not run libsumo
// still works, and a libsumo run is an error that says what is missing and what to choose.
#include <gtest/gtest.h>
#include <stdlib.h>

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
