#include "traci_server/traci_variables.hpp"

#include <libsumo/TraCIConstants.h>

namespace orch::traci {

namespace tc = libsumo;

namespace {

constexpr ServedVariable kVariables[] = {
    {Domain::Simulation, tc::VAR_TIME, "getTime"},
    {Domain::Simulation, tc::VAR_TIME_STEP, "getCurrentTime"},
    {Domain::Simulation, tc::VAR_DELTA_T, "getDeltaT"},
    {Domain::Simulation, tc::VAR_DEPARTED_VEHICLES_IDS, "getDepartedIDList"},
    {Domain::Simulation, tc::VAR_DEPARTED_VEHICLES_NUMBER, "getDepartedNumber"},
    {Domain::Simulation, tc::VAR_ARRIVED_VEHICLES_IDS, "getArrivedIDList"},
    {Domain::Simulation, tc::VAR_ARRIVED_VEHICLES_NUMBER, "getArrivedNumber"},
    {Domain::Simulation, tc::VAR_MIN_EXPECTED_VEHICLES, "getMinExpectedNumber"},
    {Domain::Vehicle, tc::TRACI_ID_LIST, "getIDList"},
    {Domain::Vehicle, tc::ID_COUNT, "getIDCount"},
    {Domain::Vehicle, tc::VAR_POSITION, "getPosition"},
    {Domain::Vehicle, tc::VAR_POSITION3D, "getPosition3D"},
    {Domain::Vehicle, tc::VAR_SPEED, "getSpeed"},
    {Domain::Vehicle, tc::VAR_ACCELERATION, "getAcceleration"},
    {Domain::Vehicle, tc::VAR_ANGLE, "getAngle"},
    {Domain::Vehicle, tc::VAR_ROAD_ID, "getRoadID"},
    {Domain::Vehicle, tc::VAR_LANE_ID, "getLaneID"},
    {Domain::Vehicle, tc::VAR_LANE_INDEX, "getLaneIndex"},
    {Domain::Vehicle, tc::VAR_LANEPOSITION, "getLanePosition"},
    {Domain::Vehicle, tc::VAR_LANEPOSITION_LAT, "getLateralLanePosition"},
    {Domain::Vehicle, tc::VAR_LENGTH, "getLength"},
    {Domain::Vehicle, tc::VAR_WIDTH, "getWidth"},
    {Domain::Vehicle, tc::VAR_TYPE, "getTypeID"},
    {Domain::Vehicle, tc::VAR_SIGNALS, "getSignals"},
    {Domain::Vehicle, tc::VAR_LEADER, "getLeader"},
    {Domain::Vehicle, tc::VAR_PARAMETER, "getParameter"},
    {Domain::Vehicle, tc::VAR_PARAMETER_WITH_KEY, "getParameterWithKey", false},
    {Domain::Vehicle, tc::VAR_SPEEDSETMODE, "getSpeedMode"},
    {Domain::Vehicle, tc::VAR_LANECHANGE_MODE, "getLaneChangeMode"},
    {Domain::Person, tc::TRACI_ID_LIST, "getIDList"},
    {Domain::Person, tc::ID_COUNT, "getIDCount"},
    {Domain::Person, tc::VAR_POSITION, "getPosition"},
    {Domain::Person, tc::VAR_POSITION3D, "getPosition3D"},
    {Domain::Person, tc::VAR_SPEED, "getSpeed"},
    {Domain::Person, tc::VAR_ANGLE, "getAngle"},
    {Domain::Person, tc::VAR_ROAD_ID, "getRoadID"},
    {Domain::Person, tc::VAR_LANE_ID, "getLaneID"},
    {Domain::Person, tc::VAR_LANEPOSITION, "getLanePosition"},
    {Domain::Person, tc::VAR_LENGTH, "getLength"},
    {Domain::Person, tc::VAR_WIDTH, "getWidth"},
    {Domain::Person, tc::VAR_TYPE, "getTypeID"},
};

constexpr ServedSetter kSetters[] = {
    {tc::VAR_SPEED, "setSpeed"},
    {tc::CMD_SLOWDOWN, "slowDown"},
    {tc::CMD_CHANGELANE, "changeLane"},
    {tc::MOVE_TO_XY, "moveToXY"},
    {tc::VAR_SIGNALS, "setSignals"},
    {tc::VAR_SPEEDSETMODE, "setSpeedMode"},
    {tc::VAR_LANECHANGE_MODE, "setLaneChangeMode"},
};

const ServedVariable* find(Domain domain, int variable) {
  for (const auto& v : kVariables)
    if (v.domain == domain && v.variable == variable) return &v;
  return nullptr;
}

}  // namespace

std::span<const ServedVariable> served_variables() { return kVariables; }
std::span<const ServedSetter> served_setters() { return kSetters; }

bool world_reads(Domain domain, int variable) {
  const ServedVariable* v = find(domain, variable);
  return v != nullptr && v->read_from_world;
}

const char* getter_name(bool simulation, int variable) {
  if (simulation) {
    if (variable == tc::VAR_PARAMETER) return "getParameter";  // named in messages, not served
    const ServedVariable* v = find(Domain::Simulation, variable);
    return v ? v->getter : nullptr;
  }
  // Other domains' get commands (lane, edge, ...) are named like the vehicle's.
  const ServedVariable* v = find(Domain::Vehicle, variable);
  return v ? v->getter : nullptr;
}

const char* setter_name(int variable) {
  for (const auto& s : kSetters)
    if (s.variable == variable) return s.name;
  return nullptr;
}

}  // namespace orch::traci
