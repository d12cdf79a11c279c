#include "run/ssm_device.hpp"

#include <fmt/format.h>

#include "metrics/following.hpp"

namespace orch {

std::vector<std::string> ssm_device_arguments(const std::string& sumo_id, const std::filesystem::path& file) {
  return {
      "--device.ssm.explicit", sumo_id,
      "--device.ssm.file", std::filesystem::absolute(file).string(),
      // Conflict measures (per foe) and global ones (the ego's own, per step); one threshold
      // per measure, in the same order. BR, SGAP and TGAP are written every step anyway.
      "--device.ssm.measures", "TTC DRAC PET BR SGAP TGAP",
      "--device.ssm.thresholds", "1000 0 1000 0 1000 1000",
      // Every step's values, not only each conflict's extremes.
      "--device.ssm.trajectories", "true",
      // As far as the orchestrator looks for leaders (metrics/following.hpp).
      "--device.ssm.range", fmt::format("{:g}", metrics::kFollowingRange),
  };
}

}  // namespace orch
