#include <gtest/gtest.h>

#include "scenario_executor_engine/conditions.hpp"
#include "support/scenario_text.hpp"

using namespace orch;
using namespace orch::engine;
using namespace orch::scenario;

namespace {

const char* kTwoCars = R"({
  "map_id": "m",
  "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"},
             "others": [{"actor_id": 1, "model_id": "vehicle.audi.tt"}]},
  "scenario": {
    "opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 0}},
                      "others": [{"actor_id": 1, "start_position": {"type": "waypoint", "wp_id": "Waypoint02", "wp_idx": 50}}],
                      "next_scenes": [1]},
    "scenes": [],
    "ending_scenes": [{"scene_id": 1}]
  }
})";

class Conditions : public ::testing::Test {
 protected:
  Conditions() : scenario_(test::scenario_from(kTwoCars)), catalog_(Catalog::embedded()), actors_(scenario_, catalog_) {
    waypoints_ = test::three_lane_road();
  }
  ActorState car(ActorId id, double x, double y, double speed) {
    ActorState a;
    a.id = id;
    a.present = true;
    a.position = Vec2(x, y);
    a.speed = speed;
    return a;
  }
  WorldSnapshot snap(double t, std::vector<ActorState> actors) {
    WorldSnapshot s;
    s.time = t;
    s.actors = std::move(actors);
    return s;
  }
  ConditionOutcome eval(const ConditionKind& k, const WorldSnapshot& now, const WorldSnapshot* before = nullptr) {
    ConditionContext ctx{now, before, actors_, waypoints_,
                         [this](ActorId) { return waypoints_.find("Waypoint02"); },
                         [this](ActorId id) { return id == collided_; },
                         {}, {}};
    return evaluate(Condition{k, "", {}}, ctx);
  }
  Scenario scenario_;
  Catalog catalog_;
  ActorTable actors_;
  WaypointFile waypoints_;
  ActorId collided_ = -1;
};

}  // namespace

TEST_F(Conditions, PositionReachCatchesAnActorThatJumpsOverTheWaypoint) {
  PositionCondition c{1, WaypointRef{"Waypoint02", 100, {}}, 1.0};
  const auto before = snap(1.0, {car(1, 97.0, -8.0, 30)});
  const auto now = snap(1.05, {car(1, 104.0, -8.0, 30)});  // 7 m in one step, over x=100
  EXPECT_TRUE(eval(c, now, &before).holds);
  EXPECT_FALSE(eval(c, now).holds);  // without the previous step it is 4 m away
  const auto beside = snap(1.05, {car(1, 100.0, -4.5, 30)});  // next lane: 3.5 m off
  EXPECT_FALSE(eval(c, beside, &before).holds);
}

TEST_F(Conditions, PositionPastTheRouteEndMeansTheLastPoint) {
  PositionCondition c{1, WaypointRef{"Waypoint02", 10000, {}}, 1.0};
  EXPECT_TRUE(eval(c, snap(1, {car(1, 2000.2, -8.0, 0)})).holds);
  EXPECT_FALSE(eval(c, snap(1, {car(1, 1990, -8.0, 0)})).holds);
}

TEST_F(Conditions, SpeedAbsoluteAndRelative) {
  const auto now = snap(1, {car(0, 0, -8, 60 / 3.6), car(1, 50, -8, 50 / 3.6)});
  EXPECT_TRUE(eval(SpeedCondition{0, SpeedType::Absolute, {}, Comparison::GreaterEqual, 60 / 3.6}, now).holds);
  EXPECT_FALSE(eval(SpeedCondition{0, SpeedType::Absolute, {}, Comparison::Greater, 60 / 3.6}, now).holds);
  // relative = actor minus target: 50 - 60 = -10 km/h
  EXPECT_TRUE(eval(SpeedCondition{1, SpeedType::Relative, 0, Comparison::Less, -9 / 3.6}, now).holds);
  EXPECT_FALSE(eval(SpeedCondition{1, SpeedType::Relative, 0, Comparison::Less, -11 / 3.6}, now).holds);
}

TEST_F(Conditions, EqualFiresWhenTheValueIsCrossedBetweenSteps) {
  SimulationTimeCondition c{Comparison::Equal, 10.02};
  const auto before = snap(10.0, {});
  const auto now = snap(10.05, {});
  EXPECT_TRUE(eval(c, now, &before).holds);
  const auto later = snap(10.10, {});
  EXPECT_FALSE(eval(c, later, &now).holds);  // only on the step that crosses it
}

TEST_F(Conditions, SimulationTimeEveryComparison) {
  const auto now = snap(5.0, {});
  EXPECT_TRUE(eval(SimulationTimeCondition{Comparison::GreaterEqual, 5.0}, now).holds);
  EXPECT_FALSE(eval(SimulationTimeCondition{Comparison::Greater, 5.0}, now).holds);
  EXPECT_TRUE(eval(SimulationTimeCondition{Comparison::LessEqual, 5.0}, now).holds);
  EXPECT_FALSE(eval(SimulationTimeCondition{Comparison::Less, 5.0}, now).holds);
  EXPECT_TRUE(eval(SimulationTimeCondition{Comparison::Equal, 5.0}, now).holds);
}

TEST_F(Conditions, OnlyAConditionThatHoldsDescribesWhatWasMeasured) {
  // The run log names the conditions that fired; the others are not formatted every step.
  const auto now = snap(5.0, {car(0, 0, -8, 20)});
  const auto fired = eval(SimulationTimeCondition{Comparison::GreaterEqual, 5.0}, now);
  EXPECT_EQ(fired.detail, "simulation time 5.00 s >= 5");
  EXPECT_EQ(eval(SimulationTimeCondition{Comparison::Greater, 5.0}, now).detail, "");
  const auto fast = eval(SpeedCondition{0, SpeedType::Absolute, {}, Comparison::GreaterEqual, 10}, now);
  EXPECT_TRUE(fast.holds);
  EXPECT_EQ(fast.detail, "speed of actor 0 72.00 km/h >= 36.00");
  const auto slow = eval(SpeedCondition{0, SpeedType::Absolute, {}, Comparison::Less, 10}, now);
  EXPECT_FALSE(slow.holds);
  EXPECT_EQ(slow.detail, "");
}

TEST_F(Conditions, TraveledDistanceSignAndSurface) {
  // Target 30 m ahead, lengths 4.51 (prius) and 4.18 (tt): surface gap 30 - 4.345.
  const auto now = snap(1, {car(0, 10, -8, 0), car(1, 40, -8, 0)});
  EXPECT_TRUE(eval(DistanceCondition{0, 1, DistanceType::Traveled, Comparison::Less, 30.1, MeasureType::Center}, now).holds);
  EXPECT_FALSE(eval(DistanceCondition{0, 1, DistanceType::Traveled, Comparison::Less, 29.9, MeasureType::Center}, now).holds);
  EXPECT_TRUE(eval(DistanceCondition{0, 1, DistanceType::Traveled, Comparison::Less, 25.7, MeasureType::Surface}, now).holds);
  EXPECT_FALSE(eval(DistanceCondition{0, 1, DistanceType::Traveled, Comparison::Less, 25.6, MeasureType::Surface}, now).holds);
  // Seen from the car ahead the ego is behind: a negative value asks about "behind".
  EXPECT_TRUE(eval(DistanceCondition{1, 0, DistanceType::Traveled, Comparison::Less, -31, MeasureType::Center}, now).holds);
  EXPECT_FALSE(eval(DistanceCondition{1, 0, DistanceType::Traveled, Comparison::Less, 31, MeasureType::Center}, now).holds);
}

TEST_F(Conditions, TraveledDistanceCountsInTheActorsDirectionOfTravel) {
  // An actor driving its route against the drawn direction (in a lane of the opposite side):
  // a target at smaller x is ahead of it.
  const auto now = snap(1, {car(0, 40, -8, 0), car(1, 10, -8, 0)});
  ConditionContext ctx{now, nullptr, actors_, waypoints_, [this](ActorId) { return waypoints_.find("Waypoint02"); },
                       [](ActorId) { return false; }, [](ActorId id) { return id == 0 ? -1 : 1; }, {}};
  DistanceCondition ahead{0, 1, DistanceType::Traveled, Comparison::Greater, 29.9, MeasureType::Center};
  EXPECT_TRUE(evaluate(Condition{ahead, "", {}}, ctx).holds);
  ctx.direction_of = nullptr;  // the same pair seen along the route as drawn: target behind
  EXPECT_FALSE(evaluate(Condition{ahead, "", {}}, ctx).holds);
}

TEST_F(Conditions, SurfaceDistanceOfOverlappingActorsIsZero) {
  const auto now = snap(1, {car(0, 10, -8, 0), car(1, 12, -8, 0)});
  EXPECT_TRUE(eval(DistanceCondition{0, 1, DistanceType::Traveled, Comparison::Equal, 0, MeasureType::Surface}, now).holds);
}

TEST_F(Conditions, TimeHeadwayAtSpeedZeroAndAfterPassing) {
  TimeHeadwayCondition c{0, WaypointRef{"Waypoint02", 100, {}}, Comparison::LessEqual, 3.0};
  // Front of the prius at 60 + 2.255; 37.745 m at 15 m/s = 2.52 s.
  EXPECT_TRUE(eval(c, snap(1, {car(0, 60, -8, 15)})).holds);
  EXPECT_FALSE(eval(c, snap(1, {car(0, 60, -8, 10)})).holds);  // 3.77 s
  EXPECT_FALSE(eval(c, snap(1, {car(0, 60, -8, 0)})).holds);   // standing: never arrives
  TimeHeadwayCondition greater{0, WaypointRef{"Waypoint02", 100, {}}, Comparison::Greater, 3.0};
  EXPECT_TRUE(eval(greater, snap(1, {car(0, 60, -8, 0)})).holds);
  EXPECT_FALSE(eval(c, snap(1, {car(0, 120, -8, 15)})).holds);  // passed: no headway
  EXPECT_FALSE(eval(greater, snap(1, {car(0, 120, -8, 15)})).holds);
}

TEST_F(Conditions, CollisionUsesTheReportedContacts) {
  const auto now = snap(1, {car(0, 0, -8, 0)});
  EXPECT_FALSE(eval(CollisionCondition{0, {}}, now).holds);
  collided_ = 0;
  EXPECT_TRUE(eval(CollisionCondition{0, {}}, now).holds);
}

TEST_F(Conditions, CollisionWithATargetHoldsOnlyForThatPair) {
  // Real files write "target_actor_id" on collision conditions: then only a contact of the
  // actor with that target counts, not one with anybody else.
  const auto now = snap(1, {car(0, 0, -8, 0), car(1, 4, -8, 0)});
  std::pair<ActorId, ActorId> touching{-1, -1};
  ConditionContext ctx{now, nullptr, actors_, waypoints_, [this](ActorId) { return waypoints_.find("Waypoint02"); },
                       [](ActorId) { return true; }, {},
                       [&](ActorId a, ActorId b) {
                         return (a == touching.first && b == touching.second) ||
                                (a == touching.second && b == touching.first);
                       }};
  const CollisionCondition with_1{0, ActorId{1}};
  EXPECT_FALSE(evaluate(Condition{with_1, "", {}}, ctx).holds);  // the ego touches something else
  touching = {1, 0};
  const auto outcome = evaluate(Condition{with_1, "", {}}, ctx);
  EXPECT_TRUE(outcome.holds);
  EXPECT_EQ(outcome.detail, "actor 0 collided with actor 1");
  EXPECT_FALSE(evaluate(Condition{CollisionCondition{0, ActorId{2}}, "", {}}, ctx).holds);
}

TEST_F(Conditions, AbsentActorsNeverSatisfyAConditionAboutThem) {
  auto gone = car(1, 50, -8, 30);
  gone.present = false;
  EXPECT_FALSE(eval(SpeedCondition{1, SpeedType::Absolute, {}, Comparison::GreaterEqual, 0}, snap(1, {gone})).holds);
}

TEST(ConditionGroups, AndOrAndNesting) {
  auto s = test::scenario_from(R"({
    "map_id": "m",
    "actors": {"ego": {"actor_id": 0, "model_id": "vehicle.toyota.prius"}},
    "scenario": {
      "opening_scene": {"ego": {"start_position": {"wp_id": "Waypoint02", "wp_idx": 0}}, "next_scenes": [1]},
      "scenes": [],
      "ending_scenes": [{"scene_id": 1, "conditions": {"and": [
          {"simulation_time": {"comparison": ">=", "value": 2}},
          {"or": [{"simulation_time": {"comparison": ">=", "value": 5}},
                  {"speed": {"actor_id": 0, "type": "absolute", "comparison": ">=", "value": 36}}]}]}}]
    }})");
  Catalog catalog = Catalog::embedded();
  ActorTable actors(s, catalog);
  WaypointFile wps = test::three_lane_road();
  auto check = [&](double t, double speed) {
    WorldSnapshot now;
    now.time = t;
    ActorState ego;
    ego.id = 0;
    ego.present = true;
    ego.speed = speed;
    now.actors = {ego};
    ConditionContext ctx{now, nullptr, actors, wps, [](ActorId) { return nullptr; }, [](ActorId) { return false; }, {}, {}};
    std::vector<std::string> fired;
    return evaluate(s.find_scene(1)->conditions, ctx, &fired);
  };
  EXPECT_FALSE(check(1.0, 20));  // and: time not yet 2
  EXPECT_TRUE(check(2.0, 10));   // speed 36 km/h reached
  EXPECT_FALSE(check(3.0, 9));   // neither or-branch
  EXPECT_TRUE(check(5.0, 0));    // time branch
}
