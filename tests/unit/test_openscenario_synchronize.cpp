// SynchronizeAction's control law (openscenario/synchronize.hpp): on a straight road, the
// entity reaches its target when the master reaches its own, at the final speed, with the
// steady state before it, stopping and waiting when it is too early.
#include <gtest/gtest.h>

#include <cmath>

#include "openscenario/synchronize.hpp"

namespace orch::openscenario {
namespace {

struct Arrival {
  double distance = 0;         // the entity's distance to its target when the action ended
  double master_distance = 0;  // the master's
  double speed = 0;            // the entity's speed then
  double min_speed = 1e9;      // the lowest speed on the way
  double speed_at_steady = -1; // the speed when the entity was 5 m into its steady state
  int steps = 0;
};

// Both entities drive straight at their targets, dt = 0.05 s; the master at constant speed.
Arrival run(double distance, double speed, double master_distance, double master_speed,
            std::optional<double> final_speed, std::optional<double> steady = std::nullopt, double tolerance = 0.0) {
  SynchronizeProgress progress;
  Arrival out;
  const double dt = 0.05;
  for (int i = 0; i < 20000; ++i) {
    SynchronizeMeasures m;
    m.distance = distance;
    m.master_distance = master_distance;
    m.master_speed = master_speed;
    m.speed = speed;
    m.speed_along = speed;
    m.dt = dt;
    m.final_speed = final_speed;
    m.steady_distance = steady;
    m.tolerance = m.tolerance_master = tolerance;
    const SynchronizeStep step = synchronize_step(progress, m);
    speed = step.speed;
    out.min_speed = std::min(out.min_speed, speed);
    if (steady && out.speed_at_steady < 0 && distance < *steady - 5) out.speed_at_steady = speed;
    if (step.done) break;
    distance = std::abs(distance - speed * dt);
    master_distance = std::abs(master_distance - master_speed * dt);
    out.steps = i + 1;
  }
  out.distance = distance;
  out.master_distance = master_distance;
  out.speed = speed;
  return out;
}

TEST(SynchronizeAction, WithoutFinalSpeedArrivesWithTheMaster) {
  // 150 m to go while the master needs 5 s for its 50 m: faster than now (10 m/s).
  const Arrival a = run(150, 10, 50, 10, std::nullopt);
  EXPECT_LT(a.distance, 1.0);
  EXPECT_LT(a.master_distance, 1.0);
  EXPECT_NEAR(a.steps * 0.05, 5.0, 0.1);
}

TEST(SynchronizeAction, ReachesTheAbsoluteFinalSpeedOnArrival) {
  // Rush then slow down to 5 m/s (convex), and linger then speed up to 20 m/s (concave).
  for (const double final_speed : {5.0, 20.0}) {
    const Arrival a = run(120, 10, 80, 10, final_speed);
    EXPECT_LT(a.distance, 1.0) << final_speed;
    EXPECT_LT(a.master_distance, 1.0) << final_speed;
    EXPECT_NEAR(a.speed, final_speed, 1e-9) << final_speed;  // set on arrival
  }
}

TEST(SynchronizeAction, KeepsTheFinalSpeedOverTheSteadyStateDistance) {
  const Arrival a = run(200, 10, 100, 10, 8.0, 30.0);
  EXPECT_LT(a.distance, 1.0);
  EXPECT_NEAR(a.speed_at_steady, 8.0, 1e-9);
}

TEST(SynchronizeAction, StopsAndWaitsWhenFarTooEarly) {
  // 30 m at 15 m/s while the master needs 20 s: brake to a stop, wait, go again.
  const Arrival a = run(30, 15, 200, 10, 5.0);
  EXPECT_EQ(a.min_speed, 0.0);
  EXPECT_LT(a.distance, 1.5);
  EXPECT_LT(a.master_distance, 1.0);
}

TEST(SynchronizeAction, EndsWithinTheTolerance) {
  const Arrival a = run(100, 10, 100, 10, std::nullopt, std::nullopt, 1.0);
  EXPECT_LE(a.distance, 1.0 + 0.5 + 1e-9);  // within the tolerance (and one step)
  EXPECT_EQ(a.steps, static_cast<int>(std::lround((100 - 1.0) / 0.5)));
}

}  // namespace
}  // namespace orch::openscenario
