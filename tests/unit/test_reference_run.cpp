// The pieces around the reference driver that need no SUMO: preventable or not, the batch's
// preventable column, the OpenSCENARIO controller that asks for the reference driver, and
// the driver's view of a snapshot.
#include <gtest/gtest.h>

#include "batch/batch_metrics_csv.hpp"
#include "reference_driver/ego_model.hpp"
#include "reference_driver/reference_ego.hpp"
#include "run/openscenario_world.hpp"
#include "run/reference_run.hpp"

using namespace orch;

TEST(ReferenceRun, PreventableUnavoidableOrNoCollision) {
  const CollisionFact hit{"actor 1", 17.45, 6.2};
  EXPECT_EQ(preventability(hit, std::nullopt), "preventable");
  EXPECT_EQ(preventability(hit, hit), "unavoidable");
  EXPECT_EQ(preventability(std::nullopt, std::nullopt), "no_collision");
  // The reference driver colliding where the run did not is still no collision of the run.
  EXPECT_EQ(preventability(std::nullopt, hit), "no_collision");
}

// Unavoidable means the same conflict: the same other road user, at about the same place in
// the story (within kSameConflictWindow). Without story places, the same time: a collision
// with actor 1 at 17.45 s and one at 23.20 s are different conflicts.
TEST(ReferenceRun, UnavoidableOnlyForTheSameConflict) {
  const CollisionFact run{"actor 1", 17.45, 6.2};
  EXPECT_EQ(preventability(run, CollisionFact{"actor 1", 23.20, 7.1}), "preventable");
  EXPECT_EQ(preventability(run, CollisionFact{"actor 2", 17.45, 6.2}), "preventable");
  EXPECT_EQ(preventability(run, CollisionFact{"actor 1", 17.45 + kSameConflictWindow - 0.01, 3.0}), "unavoidable");
  EXPECT_EQ(preventability(run, CollisionFact{"actor 1", 17.45 - 1.0, 3.0}), "unavoidable");
  EXPECT_EQ(preventability(run, CollisionFact{"actor 1", 17.45 + kSameConflictWindow + 0.01, 3.0}), "preventable");
}

TEST(ReferenceRun, BatchMetricsCsvHasThePreventableColumn) {
  batch::BatchReport report;
  for (const char* id : {"a", "b"}) report.planned.push_back({id, "L", std::string("P") + id, "", {}});
  batch::ExecutionSummary a;
  a.run_id = "a";
  a.verdict = "failure";
  a.preventable = "preventable";
  batch::ExecutionSummary b;
  b.run_id = "b";
  b.verdict = "success";
  b.preventable = "no_collision";
  report.done["a"] = a;
  report.done["b"] = b;
  const std::string csv = batch::batch_metrics_csv(report);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "run_id,logical_uuid,parameter_uuid,seed,verdict,preventable");
  EXPECT_NE(csv.find("a,L,Pa,,failure,preventable\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("b,L,Pb,,success,no_collision\n"), std::string::npos) << csv;
}

TEST(ReferenceRun, R157ControllerMakesTheEntityTheEgo) {
  openscenario::Scenario s;
  openscenario::Entity other, ego;
  other.name = "Lead";
  ego.name = "Ego";
  ego.controller = openscenario::Controller{kR157ControllerName, {}};
  s.entities = {other, ego};
  EXPECT_EQ(choose_ego_entity(s, ""), "Ego");
}

// A lead car 30 m ahead on a straight path and one 2 m past the path's end: both are seen
// ahead in the ego's lane, at their distance along the path (the path goes on straight).
TEST(ReferenceRun, TheDriverSeesObjectsAlongItsPathAndPastItsEnd) {
  reference_driver::DrivingPath path;
  path.line = Polyline({{0, 0}, {100, 0}});
  std::vector<sim::TrackedActor> tracked(3);
  tracked[0] = {0, "ego", ActorKind::Vehicle, 4.0, 2.0};
  tracked[1] = {1, "actor1", ActorKind::Vehicle, 5.0, 2.0};
  tracked[2] = {2, "actor2", ActorKind::Vehicle, 5.0, 2.0};
  sim::WorldSnapshot snap;
  snap.time = 1.0;
  auto actor = [](int id, Vec2 position, double speed) {
    sim::ActorState a;
    a.id = id;
    a.present = true;
    a.position = position;
    a.speed = speed;
    return a;
  };
  snap.actors = {actor(0, {60, 0.2}, 10.0), actor(1, {90, 0.0}, 8.0), actor(2, {102, -3.5}, 0.0)};
  const auto view = reference_driver::perceive(snap, tracked, {}, "ego", path, -1, 150);
  ASSERT_TRUE(view);
  EXPECT_DOUBLE_EQ(view->ego.s, 60);
  EXPECT_NEAR(view->ego.d, 0.2, 1e-9);
  ASSERT_EQ(view->objects.size(), 2u);
  EXPECT_DOUBLE_EQ(view->objects[0].s, 90);
  EXPECT_DOUBLE_EQ(view->objects[0].speed_s, 8.0);
  EXPECT_DOUBLE_EQ(view->objects[1].s, 102);
  EXPECT_DOUBLE_EQ(view->objects[1].d, -3.5);
  const auto ahead = reference_driver::object_ahead(*view, 150, 0.5);
  ASSERT_TRUE(ahead.object);
  EXPECT_EQ(ahead.object->id, "actor1");
  EXPECT_DOUBLE_EQ(ahead.gap, 90 - 2.5 - (60 + 2.0));
}

// The story's clock runs with the ego: 4.4_2's cut-in scene began at 16.45 s in the run and at
// 22.20 s in the reference run (the careful driver reached 60 km/h later); both collided with
// actor 1 1.0 s into it: the same conflict. 5 s into it would be another one.
TEST(ReferenceRun, TheSameConflictIsTheSamePlaceInTheStory) {
  auto scene = [](double t, int id) {
    engine::Event e(t, engine::EventKind::Scene, "scene");
    e.scene = id;
    return e;
  };
  const std::vector<engine::Event> run_events{scene(0, 0), scene(6.5, 1), scene(16.45, 2)};
  const std::vector<engine::Event> ref_events{scene(0, 0), scene(11.2, 1), scene(22.2, 2)};
  const CollisionFact run{"actor 1", 17.45, 6.2};
  const StoryPlace run_place = story_place(run_events, 17.45);
  EXPECT_EQ(run_place.element, "scene 2");
  EXPECT_NEAR(run_place.since, 1.0, 1e-9);
  EXPECT_EQ(preventability(run, CollisionFact{"actor 1", 23.2, 7.1}, run_place, story_place(ref_events, 23.2)),
            "unavoidable");
  EXPECT_EQ(preventability(run, CollisionFact{"actor 1", 27.2, 7.1}, run_place, story_place(ref_events, 27.2)),
            "preventable");
  EXPECT_EQ(preventability(run, CollisionFact{"actor 2", 23.2, 7.1}, run_place, story_place(ref_events, 23.2)),
            "preventable");
  // OpenSCENARIO: the Event that started last.
  const std::vector<engine::Event> osc{{0.0, engine::EventKind::Storyboard, "story S startTransition"},
                                       {9.0, engine::EventKind::Storyboard, "event CutInEvent startTransition"},
                                       {9.5, engine::EventKind::Storyboard, "event CutInEvent endTransition"}};
  const StoryPlace p = story_place(osc, 10.0);
  EXPECT_EQ(p.element, "event CutInEvent");
  EXPECT_NEAR(p.since, 1.0, 1e-9);
}
