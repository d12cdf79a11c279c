// The ego TraCI server's one list of served variables (traci_server/traci_variables.hpp)
// against the documentation's table and the session's command names.
#include <gtest/gtest.h>
#include <libsumo/TraCIConstants.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "traci_server/traci_session.hpp"
#include "traci_server/traci_variables.hpp"

namespace {

using orch::traci::Domain;
namespace tc = libsumo;

// The `names` in one column of the row of docs/ego-plugin.md's "What is served" table whose
// first cell is `row` (column 1: get, 2: set / other).
std::vector<std::string> documented(const std::string& row, int column) {
  std::ifstream in(std::string(ORCH_SOURCE_DIR) + "/docs/ego-plugin.md");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| " + row + " |", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream cells_in(line.substr(1));
    for (std::string cell; std::getline(cells_in, cell, '|');) cells.push_back(cell);
    std::vector<std::string> names;
    const std::regex name("`(get|set|slow|change|move)[A-Za-z0-9]*`");
    const std::string& cell = cells.at(static_cast<std::size_t>(column));
    for (auto it = std::sregex_iterator(cell.begin(), cell.end(), name); it != std::sregex_iterator(); ++it)
      names.push_back(it->str().substr(1, it->str().size() - 2));
    return names;
  }
  ADD_FAILURE() << "no row \"" << row << "\" in docs/ego-plugin.md";
  return {};
}

std::vector<std::string> served(Domain domain) {
  std::vector<std::string> names;
  for (const auto& v : orch::traci::served_variables())
    if (v.domain == domain) names.emplace_back(v.getter);
  return names;
}

TEST(TraciVariables, DocumentationListsExactlyTheServedGetters) {
  EXPECT_EQ(documented("simulation", 1), served(Domain::Simulation));
  EXPECT_EQ(documented("vehicle", 1), served(Domain::Vehicle));
  EXPECT_EQ(documented("person", 1), served(Domain::Person));
}

TEST(TraciVariables, DocumentationListsExactlyTheEgoSetters) {
  std::vector<std::string> setters;
  for (const auto& s : orch::traci::served_setters()) setters.emplace_back(s.name);
  EXPECT_EQ(documented("vehicle", 2), setters);
}

TEST(TraciVariables, EachDomainServesAVariableOnce) {
  const auto all = orch::traci::served_variables();
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j)
      EXPECT_FALSE(all[i].domain == all[j].domain && all[i].variable == all[j].variable) << all[i].getter;
}

TEST(TraciVariables, WorldReadsWhatIsServedExceptWhatTheSessionDerives) {
  EXPECT_TRUE(orch::traci::world_reads(Domain::Vehicle, tc::VAR_LANEPOSITION_LAT));
  EXPECT_TRUE(orch::traci::world_reads(Domain::Person, tc::VAR_WIDTH));
  EXPECT_FALSE(orch::traci::world_reads(Domain::Person, tc::VAR_ACCELERATION));  // vehicles only
  EXPECT_FALSE(orch::traci::world_reads(Domain::Vehicle, tc::VAR_PARAMETER_WITH_KEY));  // from getParameter
  EXPECT_FALSE(orch::traci::world_reads(Domain::Simulation, tc::VAR_PARAMETER));
}

TEST(TraciVariables, SessionNamesCommandsFromTheList) {
  EXPECT_EQ(orch::traci::command_name(tc::CMD_GET_VEHICLE_VARIABLE, tc::VAR_LANEPOSITION_LAT),
            "vehicle.getLateralLanePosition");
  EXPECT_EQ(orch::traci::command_name(tc::CMD_GET_PERSON_VARIABLE, tc::VAR_TYPE), "person.getTypeID");
  EXPECT_EQ(orch::traci::command_name(tc::CMD_GET_SIM_VARIABLE, tc::VAR_DELTA_T), "simulation.getDeltaT");
  EXPECT_EQ(orch::traci::command_name(tc::CMD_SET_VEHICLE_VARIABLE, tc::MOVE_TO_XY), "vehicle.moveToXY");
  EXPECT_EQ(orch::traci::command_name(tc::CMD_GET_VEHICLE_VARIABLE, 0x7f), "vehicle.get 0x7f");
}

}  // namespace
