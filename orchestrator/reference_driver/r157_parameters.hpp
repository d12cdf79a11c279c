#pragma once
// The figures of the UN R157 "competent and careful human driver" (Annex 4, Appendix 3) and
// of the minimum following distance (paragraph 5.2.3.3), as the reference driver uses them.
// Every figure has a name (the key an evaluation file overrides it with) and its source;
// docs/reference-driver.md lists them.
#include <map>
#include <string>
#include <vector>

namespace orch::reference_driver {

inline constexpr double kGravity = 9.81;  // m/s^2, for "0.774 G"

struct R157Parameters {
  // Annex 4 Appendix 3: when a risk is perceived, and how the driver answers it.
  double wandering_threshold = 0.375;     // m a cut-in (or cut-out) vehicle leaves its lane centre by
  double risk_perception_time = 0.4;      // s from the risk perception point to the decision
  double brake_reaction_time = 0.75;      // s from the decision to the brake acting
  double max_deceleration = 0.774 * kGravity;  // m/s^2 (0.774 G)
  double brake_jerk = 12.65;              // m/s^3 the deceleration builds up with
  // Table 1's second braking stage: after the full wrap of the ego and a cut-in vehicle the
  // deceleration builds up (in the same 0.6 s) to 0.85 G, "derived from UN Regulation No. 152 on AEBS".
  double wrap_deceleration = 0.85 * kGravity;  // m/s^2 (0.85 G)
  double lead_deceleration_threshold = 5.0;  // m/s^2: a leader braking harder is a risk
  // When the model's own braking stops (not in the regulation; the model's rule): a vehicle
  // ahead is critical while the time to collision is below this or the gap below the
  // minimum following distance.
  double critical_ttc = 2.0;              // s
  // Paragraph 5.2.3.3: the minimum following distance never below this.
  double min_standstill_gap = 2.0;        // m
  // Normal driving (the model's own, not from the regulation): how it keeps the set speed
  // and the following distance.
  double comfort_acceleration = 1.5;      // m/s^2
  double comfort_deceleration = 3.0;      // m/s^2
  double perception_range = 150.0;        // m ahead (R157 paragraph 7.1.1 asks at least 46 m)
  double pedestrian_margin = 0.5;         // m either side of the ego's body a pedestrian counts as in its path

  // The minimum time gap of paragraph 5.2.3.3 at speed v (m/s): the table's values
  // interpolated linearly, the first value below 7.2 km/h and the last above 130 km/h.
  [[nodiscard]] double time_gap(double speed) const;
  // The minimum following distance at speed v: max(min_standstill_gap, v * time_gap(v)).
  [[nodiscard]] double min_following_distance(double speed) const;
};

// One row of the time-gap table: speed in km/h, time gap in s.
struct TimeGapRow {
  double speed_kmh;
  double time_gap_s;
};
const std::vector<TimeGapRow>& time_gap_table();

// A parameter as documented and as an evaluation file names it.
struct ParameterInfo {
  std::string name;
  std::string unit;
  std::string source;
  double R157Parameters::*field;
};
const std::vector<ParameterInfo>& parameter_infos();

// Sets the named parameters. Throws std::invalid_argument naming an unknown key (with "did
// you mean") or a value that is not positive (the wandering threshold may be 0).
void apply_overrides(R157Parameters& p, const std::map<std::string, double>& overrides);

}  // namespace orch::reference_driver
