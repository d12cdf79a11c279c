// Every sample in scenarios/ run end to end on real SUMO, each with the outcome it is
// written to produce. Together they use every condition and action of the format.
#include <gtest/gtest.h>

#include <cmath>

#include "support/cli_runner.hpp"
#include "support/trace_csv.hpp"

using namespace orch::test;

namespace {

struct SampleRun {
  TempDir out;
  CliResult cli;
  nlohmann::json result;
  explicit SampleRun(const std::string& name) {
    cli = run_cli({"run", source_path("scenarios/" + name), "--out", out.path().string(), "-q"});
    result = read_json(out / "result.json");
  }
  double entered(int scene) const {
    for (const auto& s : result["scenes"])
      if (s["scene_id"] == scene) return s["enter_time"];
    ADD_FAILURE() << "scene " << scene << " never entered";
    return NAN;
  }
};

const Trace::Row* at_time(const std::vector<Trace::Row>& rows, double t) {
  for (const auto& r : rows)
    if (std::abs(r.num("time") - t) < 1e-6) return &r;
  return nullptr;
}
// A pointer into a temporary vector would dangle (AddressSanitizer found one): refuse it.
const Trace::Row* at_time(std::vector<Trace::Row>&& rows, double t) = delete;

}  // namespace

TEST(Samples, CollisionConditionFiresOnTheStepOfContact) {
  SampleRun run("collision_stop_in_front.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;  // the ego is not involved: success
  EXPECT_EQ(run.result["ending_scene"], 2);
  Trace trace(run.out / "trace.csv");
  // First step on which the bodies overlap, from the trace alone: both on the straight
  // right lane, a2 (3.71 m) behind micra (3.65 m).
  double contact = NAN;
  const auto follower = trace.actor(1);
  const auto front = trace.actor(2);
  for (std::size_t i = 0; i < follower.size() && i < front.size(); ++i) {
    if (follower[i].num("x") + 3.71 / 2 >= front[i].num("x") - 3.65 / 2) {
      contact = follower[i].num("time");
      break;
    }
  }
  ASSERT_FALSE(std::isnan(contact));
  EXPECT_NEAR(run.entered(2), contact, 1e-9);  // not earlier, not later
  ASSERT_FALSE(run.result["collisions"].empty());
  const auto& c = run.result["collisions"][0];
  EXPECT_NEAR(c["time"].get<double>(), contact, 1e-9);
  EXPECT_EQ(c["between"], nlohmann::json::array({1, 2}));
  EXPECT_EQ(c["source"], "geometry");
  EXPECT_NEAR(c["positions"][0][0].get<double>(), at_time(follower, contact)->num("x"), 1e-3);
  EXPECT_NEAR(c["positions"][1][0].get<double>(), at_time(front, contact)->num("x"), 1e-3);
}

TEST(Samples, EgoCollisionMakesTheVerdictAFailureEvenAfterTheEnding) {
  SampleRun run("ego_rear_ended.json");
  EXPECT_EQ(run.cli.exit_code, 1) << run.cli.output;
  EXPECT_EQ(run.result["verdict"], "failure");
  EXPECT_EQ(run.result["ending_scene"], 1);  // the scenario still ran as scripted to its end
  const std::string reason = run.result["reason"];
  EXPECT_NE(reason.find("the ego collided with actor 1"), std::string::npos) << reason;
  EXPECT_DOUBLE_EQ(run.result["sim_time"].get<double>(), 10.0);
}

TEST(Samples, PedestrianCrossingMakesTheEgoBrakeAndGoOn) {
  SampleRun run("pedestrian_crossing.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  EXPECT_TRUE(run.result["collisions"].empty());
  Trace trace(run.out / "trace.csv");
  const double start = run.entered(1);  // time headway <= 5 s
  // The ego's time headway to x = 400 at the start of the crossing: (400 - front) / speed.
  const auto ego = trace.actor(0);
  const auto pedestrian = trace.actor(1);
  const auto* ego_then = at_time(ego, start);
  ASSERT_NE(ego_then, nullptr);
  const double headway = (400 - (ego_then->num("x") + 4.51 / 2)) / ego_then->num("speed");
  EXPECT_LE(headway, 5.0);
  EXPECT_GT(headway, 5.0 - 0.1);  // fired on the first step below 5 s
  // 12 m in 8 s: 1.5 m/s, straight across.
  const auto* mid = at_time(pedestrian, start + 4.0);
  ASSERT_NE(mid, nullptr);
  EXPECT_NEAR(mid->num("speed"), 1.5, 1e-3);
  EXPECT_NEAR(mid->num("x"), 400, 0.01);
  double slowest = 1e9;
  for (const auto& r : trace.actor(0))
    if (r.num("time") > start) slowest = std::min(slowest, r.num("speed"));
  // SUMO's driver sees the pedestrian once it stands on the ego's lane and brakes hard
  // (from 22.2 m/s to well under half of it) instead of running it over.
  EXPECT_LT(slowest, 11.0);
  EXPECT_EQ(run.result["ending_scene"], 3);
}

TEST(Samples, AmbulanceKeepsStationWithBeaconSirenAndHandOver) {
  SampleRun run("emergency_escort.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto amb = trace.actor(1);
  const auto van = trace.actor(2);
  const double slow = run.entered(2), fast = run.entered(3), off = run.entered(4);
  double worst = 0, hardest = 0;
  for (std::size_t i = 0; i < amb.size() && i < van.size(); ++i) {
    const double t = amb[i].num("time");
    if (t < slow || t > off) continue;
    // Along the road: both lanes run side by side 4 m apart, so the gap is the distance
    // along the ambulance's heading.
    const double dx = amb[i].num("x") - van[i].num("x"), dy = amb[i].num("y") - van[i].num("y");
    const double along = dx * std::cos(amb[i].num("heading")) + dy * std::sin(amb[i].num("heading"));
    worst = std::max(worst, std::abs(along - 15.0));
    hardest = std::max(hardest, std::abs(amb[i].num("accel")));
    const bool blue = (amb[i].integer("signals") & 2048) != 0;
    if (t > slow + 0.1 && t <= off) {
      EXPECT_TRUE(blue) << "t=" << t;
      EXPECT_EQ(amb[i].integer("siren"), 1) << "t=" << t;
    }
  }
  EXPECT_LT(worst, 0.5);     // held while the van slowed to 70 and sped up to 95 km/h
  EXPECT_LE(hardest, 4.0 + 1e-6);  // within the documented limit
  const auto* later = at_time(amb, off + 1.0);
  ASSERT_NE(later, nullptr);
  EXPECT_EQ(later->integer("signals") & 2048, 0);
  EXPECT_EQ(later->integer("siren"), 0);
  EXPECT_NEAR(at_time(amb, fast + 3.0)->num("lat_offset"), 0.8, 0.05);  // lane_offset, seen by SUMO
  ASSERT_EQ(run.result["hand_overs"].size(), 2u);
  EXPECT_EQ(run.result["hand_overs"][0]["hand_over"], true);
  EXPECT_DOUBLE_EQ(run.result["hand_overs"][0]["throttle"].get<double>(), 0.2);
  EXPECT_EQ(run.result["hand_overs"][1]["hand_over"], false);
}

TEST(Samples, LeadVehicleSwerveIsVisibleInSumosLateralPosition) {
  SampleRun run("lead_vehicle_swerve.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto lead = trace.actor(1);
  const double drift = run.entered(2), weave = run.entered(3);
  auto lat = [&](double t) { return at_time(lead, t)->num("lat_offset"); };
  EXPECT_NEAR(lat(drift + 1.0), 0.5, 0.05);   // half way through the 2 s lane_offset
  EXPECT_NEAR(lat(drift + 3.0), 1.0, 0.05);   // held
  EXPECT_NEAR(lat(weave + 3.0), -1.0, 0.05);  // route_move legs: -1 after 3 s...
  EXPECT_NEAR(lat(weave + 6.0), -1.0, 0.05);  // ...held for 4 s...
  EXPECT_NEAR(lat(weave + 10.0), 0.0, 0.05);  // ...and back to the centre after 3 more
  for (const auto& r : lead) EXPECT_EQ(r.integer("lane"), 1) << "t=" << r.num("time");
}

TEST(Samples, VehicleRouteMoveKeepsItsTimetable) {
  SampleRun run("vehicle_route_move.json");
  ASSERT_EQ(run.cli.exit_code, 0) << run.cli.output;
  Trace trace(run.out / "trace.csv");
  const auto car = trace.actor(1);
  const double go = run.entered(1);
  const auto* first = at_time(car, go + 10.0);
  const auto* second = at_time(car, go + 18.0);
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  EXPECT_NEAR(first->num("x"), 350, 0.01);
  EXPECT_NEAR(first->num("y"), -8.0, 0.01);
  EXPECT_NEAR(second->num("x"), 550, 0.01);
  EXPECT_NEAR(second->num("y"), -7.5, 0.01);
  EXPECT_NEAR(at_time(car, go + 5.0)->num("speed"), 20.0, 1e-3);   // 200 m in 10 s
  EXPECT_NEAR(at_time(car, go + 14.0)->num("speed"), 25.0, 1e-3);  // 200 m in 8 s
  EXPECT_NEAR(at_time(car, go + 25.0)->num("speed"), 25.0, 1e-3);  // and on at that speed
}

TEST(Samples, AllValidateStrictly) {
  std::vector<std::string> args{"validate", "--strict"};
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(source_path("scenarios"))) {
    if (entry.path().extension() != ".json") continue;
    args.push_back(entry.path().string());
    ++count;
  }
  ASSERT_GE(count, 10);
  const auto r = run_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(std::to_string(count) + " files checked: " + std::to_string(count) + " valid"),
            std::string::npos)
      << r.output;
}
