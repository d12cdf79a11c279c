#pragma once
// Lane keeping (docs/evaluation.md "Lane keeping"): how far the body reaches beyond its
// lane's markings, m (0 inside the lane):
//   departure = max(0, |lateral| + (W/2)|cos phi| + (L/2)|sin phi| - lane_width/2)
// lateral: the centre's offset from the lane centre; phi: heading relative to the lane.
namespace orch::metrics {

double lane_departure(double lateral, double relative_heading, double length, double width, double lane_width);

}  // namespace orch::metrics
