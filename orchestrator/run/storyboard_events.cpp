#include "run/storyboard_events.hpp"

#include <fmt/format.h>

namespace orch {

std::string storyboard_log_text(const openscenario::TransitionLog& entry) {
  return fmt::format("{} {} {}", entry.type, entry.name, entry.transition);
}

engine::Event storyboard_event(const openscenario::TransitionLog& entry) {
  const auto kind = entry.type == "action" ? engine::EventKind::Action : engine::EventKind::Storyboard;
  return engine::Event(entry.time, kind, storyboard_log_text(entry));
}

}  // namespace orch
