#pragma once
// `--ssm`: SUMO's own surrogate safety measures device (device.ssm) on the ego while SUMO
// drives it, as an independent check of the orchestrator's metrics (docs/evaluation.md
// "SUMO's SSM device"). SUMO writes its XML (conflicts with TTC, DRAC, PET per step; the
// ego's brake rate, space gap and time gap to its leader per step) into the run folder.
#include <filesystem>
#include <string>
#include <vector>

namespace orch {

// The run folder's file SUMO writes the device's output to.
inline constexpr const char* kSsmFileName = "ssm.xml";

// SUMO options equipping vehicle `sumo_id` with the device, writing to `file` (absolute:
// a SUMO joined with --connect resolves paths in its own folder). Thresholds wide enough
// that every step with a foe in range is recorded: TTC and PET below 1000 s, DRAC above 0.
std::vector<std::string> ssm_device_arguments(const std::string& sumo_id, const std::filesystem::path& file);

}  // namespace orch
