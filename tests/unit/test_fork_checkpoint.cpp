// `--fork-at SECONDS|EVENT` read (core/fork_checkpoint.hpp): a number is a time, scene:N a
// ScenarioExecutor scene, anything else a storyboard element's name; bad words are errors.
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "core/fork_checkpoint.hpp"

using namespace orch;

TEST(ForkCheckpoint, ANumberIsATimeAndAnythingElseAnEvent) {
  EXPECT_EQ(parse_fork_checkpoint("10").time_s, 10.0);
  EXPECT_EQ(parse_fork_checkpoint("2.5").text(), "2.5");
  EXPECT_EQ(parse_fork_checkpoint("0").time_s, 0.0);
  const ForkCheckpoint scene = parse_fork_checkpoint("scene:03");
  EXPECT_FALSE(scene.time_s);
  EXPECT_TRUE(scene.is_scene());
  EXPECT_EQ(scene.event, "scene:3");
  const ForkCheckpoint element = parse_fork_checkpoint("LeadBrakeEvent");
  EXPECT_FALSE(element.time_s);
  EXPECT_FALSE(element.is_scene());
  EXPECT_EQ(element.text(), "LeadBrakeEvent");
  EXPECT_EQ(parse_fork_checkpoint("10s").event, "10s");  // not a number: a name (checked against the scenario)
}

TEST(ForkCheckpoint, BadWordsAreErrors) {
  const auto message = [](const std::string& text) {
    try {
      parse_fork_checkpoint(text);
    } catch (const OrchError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("").find("give a SUMO time in seconds, scene:N"), std::string::npos);
  EXPECT_NE(message("-1").find("--fork-at -1: a time must be a number of seconds >= 0"), std::string::npos);
  EXPECT_NE(message("scene:").find("expected scene:N"), std::string::npos);
  EXPECT_NE(message("scene:x").find("expected scene:N"), std::string::npos);
  EXPECT_NE(message("scene:12345678901").find("expected scene:N"), std::string::npos);
}
