// The TraCI session on a fake world: what a plug-in may ask and do, lockstep stepping,
// subscriptions, and clean errors for everything else.
#include <gtest/gtest.h>

#include "support/fake_ego_world.hpp"
#include "traci_messages.hpp"
#include "traci_server/traci_session.hpp"

using namespace orch;
using namespace orch::test;
using Next = traci::Session::Next;

namespace {

class TraciSession : public ::testing::Test {
 protected:
  TraciSession() {
    world.vehicles["ego"] = {0, 0, 10, "E0", 1, 50, 4.5, {{"orch.hand_over", "1"}}};
    world.vehicles["actor1"] = {40, 0, 8, "E0", 1, 90, 4.6, {}};
    world.vehicles["far"] = {500, 0, 30, "E0", 0, 550, 4.0, {}};
    world.persons["actor2"] = {20, -3, 0, "E0", 0, 70, 0.3, {}};
  }
  Next handle(const std::string& body) { return session.handle(body); }
  Reply reply() { return Reply(session.take_reply()); }

  FakeEgoWorld world;
  traci::Session session{world, "test server"};
};

}  // namespace

TEST_F(TraciSession, GetVersionAnswersApi20AndTheServerName) {
  ASSERT_EQ(handle(command(tc::CMD_GETVERSION, "")), Next::Reply);
  Reply r = reply();
  const Status s = r.status();
  EXPECT_EQ(s.command, tc::CMD_GETVERSION);
  EXPECT_EQ(s.result, tc::RTYPE_OK);
  EXPECT_EQ(s.text, "");  // Python's client treats any text as an error
  EXPECT_EQ(r.result_command(), tc::CMD_GETVERSION);
  EXPECT_EQ(r.reader().int32(), 20);
  EXPECT_EQ(r.reader().string(), "test server");
}

TEST_F(TraciSession, GetsAnswerFromTheWorldAndUnknownVehiclesAreErrorsThatKeepTheSessionUp) {
  ASSERT_EQ(handle(command(tc::CMD_GET_VEHICLE_VARIABLE, get_content(tc::VAR_SPEED, "actor1")) +
                   command(tc::CMD_GET_VEHICLE_VARIABLE, get_content(tc::VAR_SPEED, "nosuch")) +
                   command(tc::CMD_GET_VEHICLE_VARIABLE, get_content(tc::VAR_LANE_INDEX, "ego"))),
            Next::Reply);
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  EXPECT_EQ(r.result_command(), tc::RESPONSE_GET_VEHICLE_VARIABLE);
  EXPECT_EQ(r.reader().ubyte(), tc::VAR_SPEED);
  EXPECT_EQ(r.reader().string(), "actor1");
  EXPECT_EQ(r.reader().typed_double("speed"), 8.0);
  const Status unknown = r.status();
  EXPECT_EQ(unknown.result, tc::RTYPE_ERR);
  EXPECT_EQ(unknown.text, "Vehicle 'nosuch' is not known");
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  r.result_command();
  r.reader().ubyte();
  r.reader().string();
  EXPECT_EQ(r.reader().typed_int("lane"), 1);
}

TEST_F(TraciSession, HandOverIsAVehicleParameterOfTheEgo) {
  traci::Writer w;
  w.ubyte(tc::VAR_PARAMETER);
  w.string("ego");
  w.typed(std::string("orch.hand_over"));
  handle(command(tc::CMD_GET_VEHICLE_VARIABLE, w.bytes()));
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  r.result_command();
  r.reader().ubyte();
  r.reader().string();
  EXPECT_EQ(r.reader().typed_string("value"), "1");
}

TEST_F(TraciSession, OtherDomainsAndVariablesAreNotImplementedAndTheSessionGoesOn) {
  ASSERT_EQ(handle(command(tc::CMD_GET_LANE_VARIABLE, get_content(tc::VAR_LENGTH, "E0_0")) +
                   command(tc::CMD_GET_VEHICLE_VARIABLE, get_content(tc::VAR_COLOR, "ego")) +
                   command(tc::CMD_GETVERSION, "")),
            Next::Reply);
  Reply r = reply();
  const Status lane = r.status();
  EXPECT_EQ(lane.command, tc::CMD_GET_LANE_VARIABLE);
  EXPECT_EQ(lane.result, tc::RTYPE_NOTIMPLEMENTED);
  EXPECT_NE(lane.text.find("not implemented"), std::string::npos) << lane.text;
  EXPECT_EQ(r.status().result, tc::RTYPE_NOTIMPLEMENTED);
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
}

TEST_F(TraciSession, OnlyTheEgoMayBeCommanded) {
  handle(set_speed("ego", 12.5) + set_speed("actor1", 0));
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  const Status refused = r.status();
  EXPECT_EQ(refused.result, tc::RTYPE_ERR);
  EXPECT_NE(refused.text.find("only the vehicle 'ego'"), std::string::npos) << refused.text;
  ASSERT_EQ(world.commands.size(), 1u);
  EXPECT_EQ(world.commands[0].first, "ego");
  EXPECT_DOUBLE_EQ(std::get<traci::SetSpeed>(world.commands[0].second).speed, 12.5);
}

TEST_F(TraciSession, ChangeLaneRelativeAddsTheEgosLaneAndSumoErrorsComeBack) {
  traci::Writer w;
  w.ubyte(tc::CMD_CHANGELANE);
  w.string("ego");
  w.ubyte(tc::TYPE_COMPOUND);
  w.int32(3);
  w.ubyte(tc::TYPE_BYTE);
  w.byte(1);
  w.typed(2.0);
  w.ubyte(tc::TYPE_BYTE);
  w.byte(1);  // relative
  traci::Writer bad;
  bad.ubyte(tc::CMD_CHANGELANE);
  bad.string("ego");
  bad.ubyte(tc::TYPE_COMPOUND);
  bad.int32(2);
  bad.ubyte(tc::TYPE_BYTE);
  bad.byte(7);
  bad.typed(2.0);
  handle(command(tc::CMD_SET_VEHICLE_VARIABLE, w.bytes()) + command(tc::CMD_SET_VEHICLE_VARIABLE, bad.bytes()));
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  const Status refused = r.status();
  EXPECT_EQ(refused.result, tc::RTYPE_ERR);
  EXPECT_EQ(refused.text, "No lane with index 7");
  ASSERT_EQ(world.commands.size(), 1u);
  EXPECT_EQ(std::get<traci::ChangeLane>(world.commands[0].second).lane, 2);  // lane 1 + 1
}

TEST_F(TraciSession, SimulationStepStopsForTheWorldAndRepliesWithSubscriptionResults) {
  ASSERT_EQ(handle(subscribe(tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE, "ego", {tc::VAR_SPEED, tc::VAR_LANEPOSITION})),
            Next::Reply);
  Reply sub = reply();
  EXPECT_EQ(sub.status().result, tc::RTYPE_OK);
  EXPECT_EQ(sub.result_command(), tc::RESPONSE_SUBSCRIBE_VEHICLE_VARIABLE);  // values at once, as SUMO

  ASSERT_EQ(handle(simstep()), Next::Step);
  EXPECT_TRUE(session.stepping());
  EXPECT_NEAR(session.target(), 0.10, 1e-12);  // one step of 0.05 s
  world.time = 0.10;
  world.vehicles["ego"].speed = 11;
  ASSERT_EQ(session.resume(), Next::Reply);
  Reply r = reply();
  EXPECT_EQ(r.status().command, tc::CMD_SIMSTEP);
  EXPECT_EQ(r.reader().int32(), 1);  // one subscription result
  EXPECT_EQ(r.result_command(), tc::RESPONSE_SUBSCRIBE_VEHICLE_VARIABLE);
  EXPECT_EQ(r.reader().string(), "ego");
  EXPECT_EQ(r.reader().ubyte(), 2);
  EXPECT_EQ(r.reader().ubyte(), tc::VAR_SPEED);
  EXPECT_EQ(r.reader().ubyte(), tc::RTYPE_OK);
  EXPECT_EQ(r.reader().typed_double("speed"), 11.0);
}

TEST_F(TraciSession, TargetTimesStepUntilThenAndPastTimesDoNotStep) {
  ASSERT_EQ(handle(simstep(2.0)), Next::Step);
  EXPECT_DOUBLE_EQ(session.target(), 2.0);
  world.time = 2.0;
  session.resume();
  reply();
  ASSERT_EQ(handle(simstep(1.0)), Next::Reply);  // SUMO: a past target does nothing
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  EXPECT_EQ(r.reader().int32(), 0);
}

TEST_F(TraciSession, CommandsAfterAStepInTheSameMessageRunAfterTheWorldAdvanced) {
  ASSERT_EQ(handle(simstep() + command(tc::CMD_GET_SIM_VARIABLE, get_content(tc::VAR_TIME, ""))), Next::Step);
  world.time = 0.10;
  ASSERT_EQ(session.resume(), Next::Reply);
  Reply r = reply();
  EXPECT_EQ(r.status().command, tc::CMD_SIMSTEP);
  EXPECT_EQ(r.reader().int32(), 0);
  EXPECT_EQ(r.status().command, tc::CMD_GET_SIM_VARIABLE);
  r.result_command();
  r.reader().ubyte();
  r.reader().string();
  EXPECT_DOUBLE_EQ(r.reader().typed_double("time"), 0.10);
}

TEST_F(TraciSession, ContextSubscriptionListsVehiclesInRangeIncludingTheEgoInIdOrder) {
  handle(subscribe_context("ego", tc::CMD_GET_VEHICLE_VARIABLE, 100, {tc::VAR_SPEED}));
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  EXPECT_EQ(r.result_command(), tc::RESPONSE_SUBSCRIBE_VEHICLE_CONTEXT);
  EXPECT_EQ(r.reader().string(), "ego");
  EXPECT_EQ(r.reader().ubyte(), tc::CMD_GET_VEHICLE_VARIABLE);
  EXPECT_EQ(r.reader().ubyte(), 1);
  ASSERT_EQ(r.reader().int32(), 2);  // "far" is 500 m away
  EXPECT_EQ(r.reader().string(), "actor1");
  EXPECT_EQ(r.reader().ubyte(), tc::VAR_SPEED);
  EXPECT_EQ(r.reader().ubyte(), tc::RTYPE_OK);
  EXPECT_EQ(r.reader().typed_double("speed"), 8.0);
  EXPECT_EQ(r.reader().string(), "ego");
}

TEST_F(TraciSession, PersonsAroundTheEgoComeFromAPersonContext) {
  traci::Writer w;
  w.float64(tc::INVALID_DOUBLE_VALUE);
  w.float64(tc::INVALID_DOUBLE_VALUE);
  w.string("ego");
  w.ubyte(tc::CMD_GET_PERSON_VARIABLE);
  w.float64(50);
  w.ubyte(1);
  w.ubyte(tc::VAR_POSITION);
  handle(command(tc::CMD_SUBSCRIBE_VEHICLE_CONTEXT, w.bytes()));
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  r.result_command();
  r.reader().string();
  EXPECT_EQ(r.reader().ubyte(), tc::CMD_GET_PERSON_VARIABLE);
  r.reader().ubyte();
  ASSERT_EQ(r.reader().int32(), 1);
  EXPECT_EQ(r.reader().string(), "actor2");
}

TEST_F(TraciSession, UnsubscribingEndsTheResultsAndUnknownVariablesCannotBeSubscribed) {
  handle(subscribe(tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE, "ego", {tc::VAR_SPEED}));
  reply();
  handle(subscribe(tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE, "ego", {}));
  EXPECT_EQ(reply().status().result, tc::RTYPE_OK);
  handle(subscribe(tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE, "ego", {tc::VAR_COLOR}));
  EXPECT_EQ(reply().status().result, tc::RTYPE_NOTIMPLEMENTED);
  handle(subscribe(tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE, "nosuch", {tc::VAR_SPEED}));
  EXPECT_EQ(reply().status().result, tc::RTYPE_ERR);
  handle(simstep());
  world.time = 0.10;
  session.resume();
  Reply r = reply();
  r.status();
  EXPECT_EQ(r.reader().int32(), 0);
}

TEST_F(TraciSession, AVehicleThatLeftEndsItsSubscription) {
  handle(subscribe(tc::CMD_SUBSCRIBE_VEHICLE_VARIABLE, "actor1", {tc::VAR_SPEED}));
  reply();
  handle(simstep());
  world.time = 0.10;
  world.vehicles.erase("actor1");
  session.resume();
  Reply r = reply();
  r.status();
  EXPECT_EQ(r.reader().int32(), 0);
}

TEST_F(TraciSession, MalformedCommandsGetAnErrorStatusAndADecodeError) {
  traci::Writer w;
  w.ubyte(tc::VAR_SPEED);
  w.string("ego");
  w.typed(std::int32_t{10});  // an int where SUMO wants a double
  EXPECT_THROW(handle(command(tc::CMD_SET_VEHICLE_VARIABLE, w.bytes())), traci::DecodeError);
  Reply r = reply();
  const Status s = r.status();
  EXPECT_EQ(s.command, tc::CMD_SET_VEHICLE_VARIABLE);
  EXPECT_EQ(s.result, tc::RTYPE_ERR);
  EXPECT_NE(s.text.find("must have type"), std::string::npos) << s.text;
  EXPECT_TRUE(world.commands.empty());

  const std::string truncated = command(tc::CMD_GET_VEHICLE_VARIABLE, get_content(tc::VAR_SPEED, "ego"));
  EXPECT_THROW(handle(truncated.substr(0, truncated.size() - 2)), traci::DecodeError);
  EXPECT_EQ(reply().status().result, tc::RTYPE_ERR);
}

TEST_F(TraciSession, AfterTheRunEndsStepsAreRefusedAndNothingIsExpected) {
  session.end_run("the scenario run has ended: verdict success");
  handle(command(tc::CMD_GET_SIM_VARIABLE, get_content(tc::VAR_MIN_EXPECTED_VEHICLES, "")) + simstep() +
         command(tc::CMD_CLOSE, ""));
  Reply r = reply();
  EXPECT_EQ(r.status().result, tc::RTYPE_OK);
  r.result_command();
  r.reader().ubyte();
  r.reader().string();
  EXPECT_EQ(r.reader().typed_int("expected"), 0);
  const Status step = r.status();
  EXPECT_EQ(step.result, tc::RTYPE_ERR);
  EXPECT_NE(step.text.find("verdict success"), std::string::npos);
}

TEST_F(TraciSession, CloseEndsTheConversationAndCountsAreKeptByName) {
  traci::Writer order;
  order.int32(3);
  traci::Writer client;
  client.ubyte(tc::VAR_PARAMETER);
  client.string("");
  client.ubyte(tc::TYPE_COMPOUND);
  client.int32(2);
  client.typed(std::string("orch.client"));
  client.typed(std::string("my stack 2.1"));
  ASSERT_EQ(handle(command(tc::CMD_SETORDER, order.bytes()) + command(tc::CMD_SET_SIM_VARIABLE, client.bytes()) +
                   set_speed("ego", 3) + set_speed("ego", 4) + command(tc::CMD_CLOSE, "")),
            Next::Close);
  const auto& stats = session.stats();
  EXPECT_EQ(stats.order, 3);
  EXPECT_EQ(stats.client, "my stack 2.1");
  EXPECT_EQ(stats.commands.at("vehicle.setSpeed"), 2);
  EXPECT_EQ(stats.commands.at("close"), 1);
  EXPECT_EQ(stats.commands.at("simulation.setParameter"), 1);
}
