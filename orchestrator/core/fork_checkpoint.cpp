#include "core/fork_checkpoint.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>

#include "core/errors.hpp"
#include "core/suggest.hpp"

namespace orch {

std::string ForkCheckpoint::text() const { return time_s ? fmt::format("{}", *time_s) : event; }

ForkCheckpoint parse_fork_checkpoint(const std::string& text) {
  if (text.empty())
    throw OrchError("--fork-at: give a SUMO time in seconds, scene:N (a ScenarioExecutor scene) or the name of an "
                    "OpenSCENARIO storyboard element");
  ForkCheckpoint c;
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec == std::errc() && ptr == end) {
    if (!std::isfinite(value) || value < 0)
      throw OrchError(fmt::format("--fork-at {}: a time must be a number of seconds >= 0", text));
    c.time_s = value;
    return c;
  }
  c.event = text;
  if (c.is_scene()) {
    const std::string id = text.substr(6);
    bool digits = !id.empty();
    for (const char ch : id) digits = digits && std::isdigit(static_cast<unsigned char>(ch));
    if (!digits || id.size() > 9)
      throw OrchError(fmt::format("--fork-at {}: expected scene:N with N a scene id of the scenario (0, 1, 2, ...)", text));
    c.event = "scene:" + std::to_string(std::stoll(id));  // scene:01 is scene:1
  }
  return c;
}

std::string unknown_event_message(const ForkCheckpoint& checkpoint, const std::string& file, bool openscenario,
                                  const std::vector<std::string>& events) {
  const std::string what = openscenario            ? "storyboard element named " + checkpoint.event
                           : checkpoint.is_scene() ? "scene " + checkpoint.event.substr(6)
                                                   : "event " + checkpoint.event + " (its events are its scenes, scene:N)";
  // Scene ids: the list says it; a "did you mean" between numbers says nothing.
  return fmt::format("--fork-at {}: {} has no {}; {}: {}{}", checkpoint.event, file, what,
                     openscenario ? "its storyboard elements (Story, Act, ManeuverGroup, Maneuver, Event, Action)"
                                  : "its scenes",
                     fmt::join(events, ", "), openscenario ? did_you_mean(checkpoint.event, events) : std::string());
}

}  // namespace orch
