// Storyboard element names that repeat in different parents, and references to them by a path
// of names ("event::action"): the pure resolution (openscenario/element_path.hpp).
#include <gtest/gtest.h>

#include "openscenario/element_path.hpp"

namespace orch::openscenario {
namespace {

using Elements = std::vector<std::pair<std::vector<std::string>, std::string>>;

TEST(ElementPath, SplitsAndJoinsOnDoubleColons) {
  EXPECT_EQ(split_path("Story::Act::Group"), (std::vector<std::string>{"Story", "Act", "Group"}));
  EXPECT_EQ(split_path("Brake"), std::vector<std::string>{"Brake"});
  EXPECT_EQ(split_path("a::"), (std::vector<std::string>{"a", ""}));
  EXPECT_EQ(join_path({"S", "A", "G"}), "S::A::G");
  EXPECT_EQ(join_path(split_path("x::y::z")), "x::y::z");
}

// Two actions named ConnectAction, in the events ConnectEvent and DisconnectEvent
// (trailer_connect.xosc of the esmini examples), and one named Reverse.
const Elements kActions = {
    {{"S", "A", "G", "M", "ConnectEvent", "ConnectAction"}, "k1"},
    {{"S", "A", "G", "M", "DisconnectEvent", "ConnectAction"}, "k2"},
    {{"S", "A", "G", "M", "ReverseEvent", "Reverse"}, "k3"},
};

TEST(ElementPath, AUniqueNameNeedsNoPath) {
  EXPECT_EQ(resolve_reference("Reverse", kActions).keys, std::vector<std::string>{"k3"});
}

TEST(ElementPath, ARepeatedNameAloneIsAmbiguous) {
  EXPECT_EQ(resolve_reference("ConnectAction", kActions).keys, (std::vector<std::string>{"k1", "k2"}));
}

TEST(ElementPath, TheParentsNamesPickOne) {
  EXPECT_EQ(resolve_reference("DisconnectEvent::ConnectAction", kActions).keys, std::vector<std::string>{"k2"});
  EXPECT_EQ(resolve_reference("S::A::G::M::ConnectEvent::ConnectAction", kActions).keys,
            std::vector<std::string>{"k1"});
  EXPECT_TRUE(resolve_reference("OtherEvent::ConnectAction", kActions).keys.empty());
  EXPECT_TRUE(resolve_reference("X::S::A::G::M::ConnectEvent::ConnectAction", kActions).keys.empty());
  EXPECT_TRUE(resolve_reference("Connect", kActions).keys.empty());  // whole names only
}

TEST(ElementPath, ANameThatHoldsDoubleColonsMatchesWhole) {
  const Elements actions = {{{"S", "A", "G", "M", "E", "lane::change"}, "k"}};
  EXPECT_EQ(resolve_reference("lane::change", actions).keys, std::vector<std::string>{"k"});
}

}  // namespace
}  // namespace orch::openscenario
