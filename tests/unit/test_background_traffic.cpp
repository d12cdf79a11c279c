// What `--traffic` accepts, and `--realtime` pacing, without SUMO.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "core/errors.hpp"
#include "map/background_traffic.hpp"
#include "run/paced_simulator.hpp"
#include "unit/synthetic_roads.hpp"

using namespace orch;

TEST(TrafficChoice, NoneAndEmptyMeanNoTraffic) {
  EXPECT_EQ(parse_traffic("").kind, TrafficChoice::Kind::None);
  EXPECT_EQ(parse_traffic("none").kind, TrafficChoice::Kind::None);
  EXPECT_EQ(parse_traffic("0").kind, TrafficChoice::Kind::None);
  EXPECT_EQ(parse_traffic("").label, "none");
}

TEST(TrafficChoice, LevelsAreVehiclesPerHourAndLane) {
  const auto light = parse_traffic("light");
  const auto dense = parse_traffic("dense");
  EXPECT_EQ(light.kind, TrafficChoice::Kind::Rate);
  EXPECT_EQ(dense.label, "dense");
  EXPECT_GT(dense.vehicles_per_hour_per_lane, parse_traffic("medium").vehicles_per_hour_per_lane);
  EXPECT_GT(parse_traffic("medium").vehicles_per_hour_per_lane, light.vehicles_per_hour_per_lane);
  const auto number = parse_traffic("1250.5");
  EXPECT_EQ(number.kind, TrafficChoice::Kind::Rate);
  EXPECT_DOUBLE_EQ(number.vehicles_per_hour_per_lane, 1250.5);
}

TEST(TrafficChoice, AnExistingFileIsARouteFile) {
  test::TempDir dir("traffic_choice");
  const auto file = dir.path() / "mine.rou.xml";
  std::ofstream(file) << "<routes/>\n";
  const auto c = parse_traffic(file.string());
  EXPECT_EQ(c.kind, TrafficChoice::Kind::File);
  EXPECT_EQ(c.file, std::filesystem::absolute(file));
}

TEST(TrafficChoice, AnythingElseIsRefusedWithTheChoices) {
  for (const char* bad : {"heavy", "-5", "12abc", "/no/such/file.rou.xml", "nan"}) {
    SCOPED_TRACE(bad);
    try {
      parse_traffic(bad);
      FAIL() << "accepted";
    } catch (const OrchError& e) {
      EXPECT_NE(std::string(e.what()).find("light, medium, dense"), std::string::npos) << e.what();
    }
  }
}

namespace {

// Counts calls; every step takes no time.
class CountingSimulator final : public Simulator {
 public:
  void start(const SimulatorConfig&) override {}
  void apply(const std::vector<sim::Command>&) override {}
  void advance() override { ++steps; }
  sim::WorldSnapshot read(const std::vector<sim::TrackedActor>&) override { return {}; }
  double time() override { return 0; }
  [[nodiscard]] std::string backend() const override { return "fake"; }
  std::string version() override { return "fake"; }
  void close() override {}
  int steps = 0;
};

}  // namespace

TEST(PacedSimulator, StepsNoFasterThanTheFactorAllows) {
  CountingSimulator inner;
  PacedSimulator paced(inner, 4.0);  // 4x real time: 10 steps of 0.1 s take at least 0.25 s
  SimulatorConfig config;
  config.step = 0.1;
  const auto t0 = std::chrono::steady_clock::now();
  paced.start(config);
  for (int i = 0; i < 10; ++i) paced.advance();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(inner.steps, 10);
  EXPECT_GE(wall, 0.25 - 1e-3);  // a lower bound only: sleep_until never wakes early
  EXPECT_EQ(paced.backend(), "fake");
}
