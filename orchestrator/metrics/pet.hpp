#pragma once
// Post-encroachment time on crossing paths (docs/evaluation.md "PET"), generic over two
// bodies' trajectories, whatever the map:
//   conflict point  where the two centre paths cross (segments at more than kMinCrossing
//                   to each other, so bodies following one another on one path have none);
//   occupancy       the times a body's rectangle covers the conflict point, from the first
//                   sample covering it to the last (sample resolution: the step);
//   PET             the later body's first covering sample minus the earlier body's last
//                   one; 0 when both cover it at once.
// The smallest PET over all conflict points of the pair.
#include <optional>
#include <vector>

#include "engine/collision.hpp"

namespace orch::metrics {

inline constexpr double kMinCrossing = 0.35;  // rad (20 degrees) between the paths

struct TrajectorySample {
  double time = 0;
  engine::Box box;
};

struct PetResult {
  double pet = 0;   // s
  double time = 0;  // s, when the later body entered the conflict point
  Vec2 point{0, 0};
};

std::optional<PetResult> post_encroachment_time(const std::vector<TrajectorySample>& a,
                                                const std::vector<TrajectorySample>& b);

// Appends a sample unless the body moved less than `min_move` m since the last kept one
// (a standing body adds nothing), keeping trajectories of long runs small. The last sample
// of a stop is still kept when the body moves on.
void append_sample(std::vector<TrajectorySample>& trajectory, const TrajectorySample& s, double min_move = 0.1);

}  // namespace orch::metrics
