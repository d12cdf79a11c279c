// `map build`'s repair of netconvert's mutual yields between two lanes of one edge and of
// links that yield to each other in a cycle
// (map/junction_right_of_way.hpp), on the junction of generated city map 200 where SUMO's
// vehicles waited for each other for ever.
#include <gtest/gtest.h>

#include "map/junction_right_of_way.hpp"

using namespace orch;

namespace {

// Junction J9 of seed 200 as netconvert 1.15 wrote it (shapes left out): lane 0 goes straight
// (link 0) or turns left (link 1), lane 1 turns partly right across it (link 2); links 1 and 2
// each yield to the other.
// With `wait_inside`, link 1 waits inside the junction (cont="1": its internal lane :J9_1_0
// leads on through :J9_3_0, which the junction lists for it, as netconvert does).
std::string net_with_links(const std::string& response1, const std::string& state1, const std::string& response2,
                           bool wait_inside = false) {
  return std::string("<net>\n") +
         "    <junction id=\"J9\" type=\"priority\" x=\"0\" y=\"0\" incLanes=\"E_0 E_1\" "
         "intLanes=\":J9_0_0 " + (wait_inside ? ":J9_3_0" : ":J9_1_0") + " :J9_2_0\" shape=\"0,0 1,1\">\n"
         "        <request index=\"0\" response=\"000\" foes=\"000\" cont=\"0\"/>\n"
         "        <request index=\"1\" response=\"" + response1 + "\" foes=\"100\" cont=\"0\"/>\n"
         "        <request index=\"2\" response=\"" + response2 + "\" foes=\"010\" cont=\"0\"/>\n"
         "    </junction>\n"
         "    <connection from=\"E\" to=\"S\" fromLane=\"0\" toLane=\"0\" via=\":J9_0_0\" dir=\"s\" state=\"M\"/>\n"
         "    <connection from=\"E\" to=\"L\" fromLane=\"0\" toLane=\"0\" via=\":J9_1_0\" dir=\"l\" state=\"" + state1 + "\"/>\n"
         "    <connection from=\"E\" to=\"R\" fromLane=\"1\" toLane=\"0\" via=\":J9_2_0\" dir=\"R\" state=\"m\"/>\n"
         + (wait_inside ? "    <connection from=\":J9_1\" to=\"L\" fromLane=\"0\" toLane=\"0\" via=\":J9_3_0\" dir=\"l\" state=\"m\"/>\n"
                        : "    <connection from=\":J9_1\" to=\"L\" fromLane=\"0\" toLane=\"0\" dir=\"l\" state=\"M\"/>\n") +
         "</net>\n";
}

}  // namespace

TEST(JunctionRightOfWay, TheRightLaneGoesWhereTwoLanesOfOneEdgeYieldToEachOther) {
  std::vector<std::string> notes;
  const std::string fixed = without_mutual_yields(net_with_links("100", "m", "010"), notes);
  // Link 1 (lane 0) no longer yields to link 2 and is major; link 2 (lane 1) still yields to it.
  EXPECT_EQ(fixed, net_with_links("000", "M", "010"));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("J9"), std::string::npos) << notes[0];
}

TEST(JunctionRightOfWay, ALinkWaitingInsideTheJunctionIsFoundThroughItsSecondInternalLane) {
  std::vector<std::string> notes;
  const std::string fixed = without_mutual_yields(net_with_links("100", "m", "010", true), notes);
  EXPECT_EQ(fixed, net_with_links("000", "M", "010", true));
  EXPECT_EQ(notes.size(), 1u);
}

TEST(JunctionRightOfWay, OneWayYieldsAreLeftAsNetconvertWroteThem) {
  std::vector<std::string> notes;
  const std::string net = net_with_links("000", "M", "010");
  EXPECT_EQ(without_mutual_yields(net, notes), net);
  EXPECT_TRUE(notes.empty());
}

namespace {

// Three approaches A, B, C whose links (0, 1, 2) yield in a cycle: 0 to 1, 1 to 2, 2 to 0 (as
// netconvert 1.15 wrote seed 449's J0, there over five approaches).
std::string net_with_cycle(const std::string& type, const std::string& r0, const std::string& r1,
                           const std::string& r2, const std::string& state0) {
  return "<net>\n"
         "    <junction id=\"J0\" type=\"" + type + "\" x=\"0\" y=\"0\" incLanes=\"A_0 B_0 C_0\" "
         "intLanes=\":J0_0_0 :J0_1_0 :J0_2_0\" shape=\"0,0 1,1\">\n"
         "        <request index=\"0\" response=\"" + r0 + "\" foes=\"110\" cont=\"0\"/>\n"
         "        <request index=\"1\" response=\"" + r1 + "\" foes=\"101\" cont=\"0\"/>\n"
         "        <request index=\"2\" response=\"" + r2 + "\" foes=\"011\" cont=\"0\"/>\n"
         "    </junction>\n"
         "    <connection from=\"A\" to=\"X\" fromLane=\"0\" toLane=\"0\" via=\":J0_0_0\" dir=\"l\" state=\"" + state0 + "\"/>\n"
         "    <connection from=\"B\" to=\"Y\" fromLane=\"0\" toLane=\"0\" via=\":J0_1_0\" dir=\"l\" state=\"m\"/>\n"
         "    <connection from=\"C\" to=\"Z\" fromLane=\"0\" toLane=\"0\" via=\":J0_2_0\" dir=\"l\" state=\"m\"/>\n"
         "</net>\n";
}

}  // namespace

TEST(JunctionRightOfWay, LinksYieldingInACycleGoInOneOrder) {
  std::vector<std::string> notes;
  const std::string fixed = without_mutual_yields(net_with_cycle("priority", "010", "100", "001", "m"), notes);
  // Each yields to one link: ranked by index, link 0 goes first (major), 1 yields to 0, 2 to 0 and 1.
  EXPECT_EQ(fixed, net_with_cycle("priority", "000", "001", "011", "M"));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("cycle"), std::string::npos) << notes[0];
}

TEST(JunctionRightOfWay, CyclesAtTrafficLightsAreLeftToThePhases) {
  std::vector<std::string> notes;
  const std::string net = net_with_cycle("traffic_light", "010", "100", "001", "m");
  EXPECT_EQ(without_mutual_yields(net, notes), net);
  EXPECT_TRUE(notes.empty());
}
