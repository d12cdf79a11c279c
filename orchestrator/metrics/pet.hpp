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
//
// TrajectoryBook keeps the trajectories of every body a run sees (the actors, and the
// background vehicles while they are near an actor), so that each measured actor's PET is
// taken against all of them.
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "sim/box.hpp"

namespace orch::metrics {

inline constexpr double kMinCrossing = 0.35;  // rad (20 degrees) between the paths

struct TrajectorySample {
  double time = 0;
  sim::Box box;
  // The body was out of sight before this sample (a background vehicle that left the
  // actors' surroundings and came back): no path between this sample and the one before.
  bool resumed = false;
};

struct PetResult {
  double pet = 0;   // s
  double time = 0;  // s, when the later body entered the conflict point
  Vec2 point{0, 0};
};

// One trajectory's path segments by grid cell, built once to be crossed with many others.
class PathCells {
 public:
  explicit PathCells(const std::vector<TrajectorySample>& path);
  [[nodiscard]] const std::vector<TrajectorySample>& path() const { return path_; }
  // Segments (index of their first sample) with an end in the cell of `p`.
  [[nodiscard]] const std::vector<std::size_t>* at(const Vec2& p) const;

 private:
  const std::vector<TrajectorySample>& path_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

std::optional<PetResult> post_encroachment_time(const PathCells& a, const std::vector<TrajectorySample>& b);
std::optional<PetResult> post_encroachment_time(const std::vector<TrajectorySample>& a,
                                                const std::vector<TrajectorySample>& b);

// Appends a sample unless the body moved less than `min_move` m since the last kept one
// (a standing body adds nothing), keeping trajectories of long runs small. The last sample
// of a stop is still kept when the body moves on.
void append_sample(std::vector<TrajectorySample>& trajectory, const TrajectorySample& s, double min_move = 0.1);

struct PetWith {
  PetResult pet;
  std::string partner;
};

class TrajectoryBook {
 public:
  struct Seen {
    std::string id;  // actor id as text, or the SUMO id of a background vehicle
    sim::Box box;
  };
  // Every body present at `time`, recorded once per step in step order. A body missing from
  // a step starts a new piece of its trajectory when it is seen again.
  void record(double time, const std::vector<Seen>& bodies);
  // The smallest PET of body `id` against every other body, with the partner; none when no
  // path crossed its own.
  [[nodiscard]] std::optional<PetWith> min_pet(const std::string& id) const;
  [[nodiscard]] std::size_t bodies() const { return trajectories_.size(); }

 private:
  struct Track {
    std::vector<TrajectorySample> samples;
    long long last_step = -1;
  };
  std::map<std::string, Track> trajectories_;
  long long step_ = -1;
};

}  // namespace orch::metrics
