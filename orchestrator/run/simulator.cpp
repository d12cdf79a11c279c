#include "run/simulator.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace orch {

std::vector<std::string> sumo_arguments(const SimulatorConfig& c) {
  std::vector<std::string> args = {
      "-n", c.net_file,
      "--step-length", fmt::format("{:g}", c.step),
      "--seed", std::to_string(c.seed),
      // Sublane model: actors' lateral offsets (lane changes, lane_offset) are seen by SUMO.
      "--lateral-resolution", "0.8",
      // Report every physical contact; never teleport or remove a vehicle, which would
      // silently change the scenario (an ego waiting behind an obstacle must keep waiting).
      "--collision.action", "warn",
      "--collision.check-junctions", "true",
      "--collision.mingap-factor", "0",
      "--time-to-teleport", "-1",
      // A vehicle standing inside a junction for this long no longer blocks the vehicles
      // with right of way behind it: dense traffic cannot lock a junction up for good
      // (counts.csv counts vehicles standing longer than 60 s).
      "--ignore-junction-blocker", "20",
      "--no-step-log", "true",
      "--duration-log.disable", "true",
  };
  if (!c.route_files.empty()) {
    args.push_back("-r");
    args.push_back(fmt::format("{}", fmt::join(c.route_files, ",")));
    // A background vehicle that finds no room to enter within this time is dropped, so
    // that a level above the road's capacity cannot pile up waiting vehicles (memory)
    // during a long run. Scenario actors enter at t=0, before any background traffic.
    args.insert(args.end(), {"--max-depart-delay", "10"});
  }
  if (!c.log_file.empty()) {
    args.push_back("--log");
    args.push_back(c.log_file);
  }
  args.insert(args.end(), c.extra_args.begin(), c.extra_args.end());
  return args;
}

}  // namespace orch
