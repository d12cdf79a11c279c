#include "run/openscenario_signals.hpp"

#include <cctype>
#include <sstream>
#include <utility>

namespace orch {

namespace {

std::string lower_trimmed(const std::string& text) {
  std::string out;
  for (const char c : text)
    if (std::isspace(static_cast<unsigned char>(c)) == 0) out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

// How much a colour holds traffic back: the most restrictive wins a shared link.
int restriction(char colour) {
  switch (colour) {
    case 'r': return 5;
    case 'u': return 4;
    case 'y': return 3;
    case 'o': return 2;
    case 'O': return 1;
    default: return 0;  // 'G', 'g'
  }
}

}  // namespace

std::optional<SumoSignalColour> sumo_signal_colour(const std::string& state) {
  const std::string s = lower_trimmed(state);
  if (s == "red") return SumoSignalColour{'r', true};
  if (s == "yellow" || s == "amber") return SumoSignalColour{'y', true};
  if (s == "red-yellow" || s == "redyellow" || s == "red_yellow") return SumoSignalColour{'u', true};
  if (s == "green") return SumoSignalColour{'G', true};
  if (s == "off") return SumoSignalColour{'O', false};
  std::vector<std::string> lamps;
  std::istringstream in(s);
  for (std::string lamp; std::getline(in, lamp, ';');) {
    if (lamp != "on" && lamp != "off" && lamp != "flashing") return std::nullopt;
    lamps.push_back(lamp);
  }
  const auto on = [&](std::size_t i) { return lamps[i] == "on"; };
  if (lamps.size() == 3) {
    if (on(0) && on(1)) return SumoSignalColour{'u', true};
    if (on(0)) return SumoSignalColour{'r', true};
    if (on(1)) return SumoSignalColour{'y', true};
    if (on(2)) return SumoSignalColour{'G', true};
    if (lamps[1] == "flashing") return SumoSignalColour{'o', true};
    return SumoSignalColour{'O', true};
  }
  if (lamps.size() == 2) {
    if (on(0)) return SumoSignalColour{'r', false};
    if (on(1)) return SumoSignalColour{'G', false};
    return SumoSignalColour{'O', false};
  }
  return std::nullopt;
}

std::vector<sim::Command> OpenScenarioSignals::update(const std::map<std::string, std::string>& states) {
  // tls -> link -> (from a vehicle signal, colour) chosen so far
  std::map<std::string, std::map<int, SumoSignalColour>> chosen;
  for (const auto& [signal, state] : states) {
    const auto links = links_.by_signal.find(signal);
    if (links == links_.by_signal.end()) {
      if (unlinked_seen_.insert(signal).second) unlinked_new_.push_back(signal);
      continue;
    }
    const auto colour = sumo_signal_colour(state);
    if (!colour) continue;
    for (const opendrive::SumoSignalLink& l : links->second) {
      auto [it, fresh] = chosen[l.tls].try_emplace(l.link, *colour);
      if (fresh) continue;
      SumoSignalColour& have = it->second;
      if (colour->vehicle != have.vehicle) {
        if (colour->vehicle) have = *colour;
      } else if (restriction(colour->colour) > restriction(have.colour)) {
        have = *colour;
      }
    }
  }
  std::vector<sim::Command> out;
  for (const auto& [tls, links] : chosen) {
    std::string text(static_cast<std::size_t>(links_.link_counts.at(tls)), '-');
    for (const auto& [link, colour] : links) text[static_cast<std::size_t>(link)] = colour.colour;
    std::string& sent = sent_[tls];
    if (sent == text) continue;
    sent = text;
    out.push_back(sim::SetTrafficLight{tls, text});
  }
  return out;
}

std::vector<std::string> OpenScenarioSignals::take_unlinked() { return std::exchange(unlinked_new_, {}); }

}  // namespace orch
