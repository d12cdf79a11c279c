#pragma once
// Positions another OpenSCENARIO player (esmini) computes for the OSC-ALKS scenarios, from
// ../shared/data/openscenario/README.md: reference point, heading, speed at a time.
#include <ostream>

namespace orch::test {

struct Reference {
  const char* file;
  double time;
  const char* entity;
  double x, y, heading, speed;
};
inline void PrintTo(const Reference& r, std::ostream* os) { *os << r.file << " " << r.entity << " @" << r.time; }

inline const Reference kAlksReferences[] = {
    {"alks_scenario_4_1_1_free_driving_template", 70.000, "Ego", 928.843, 434.766, 0.737, 16.667},
    {"alks_scenario_4_1_2_swerving_lead_vehicle_template", 22.150, "LeadVehicle", 412.500, -7.047, 6.256, 16.667},
    {"alks_scenario_4_2_1_fully_blocking_target_template", 22.000, "Ego", 371.667, -8.000, 0, 16.667},
    {"alks_scenario_4_2_4_multiple_blocking_targets_template", 0.000, "Ego", 5.000, -8.000, 0, 16.667},
    {"alks_scenario_4_2_4_multiple_blocking_targets_template", 0.000, "TargetBlocking", 500.000, -8.000, 0, 0},
    {"alks_scenario_4_2_4_multiple_blocking_targets_template", 22.500, "Ego", 380.000, -8.000, 0, 16.667},
    {"alks_scenario_4_3_1_follow_lead_vehicle_comfortable_template", 21.000, "LeadVehicle", 429.292, -8.000, 0, 21.667},
    {"alks_scenario_4_3_1_follow_lead_vehicle_comfortable_template", 54.400, "LeadVehicle", 908.708, -8.000, 0, 11.667},
    {"alks_scenario_4_4_1_cut_in_no_collision_template", 8.050, "CutInVehicle", 180.000, -11.500, 0, 11.111},
    {"alks_scenario_4_4_1_cut_in_no_collision_template", 10.400, "CutInVehicle", 206.005, -9.899, 0.179, 11.111},
    {"alks_scenario_4_4_1_cut_in_no_collision_template", 13.500, "CutInVehicle", 240.307, -8.000, 0, 11.111},
    {"alks_scenario_4_5_1_cut_out_fully_blocking_template", 24.500, "LeadVehicle", 451.666, -7.898, 0.034, 16.667},
    {"alks_scenario_4_5_1_cut_out_fully_blocking_template", 30.000, "LeadVehicle", 543.168, -4.500, 0, 16.667},
    {"alks_scenario_4_5_1_cut_out_fully_blocking_template", 30.000, "TargetBlocking", 500.000, -8.000, 0, 0},
    {"alks_scenario_4_6_1_forward_detection_range_template", 29.500, "TargetBlocking", 500.000, -13.250, 0, 0},
};

}  // namespace orch::test
