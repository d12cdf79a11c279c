#include "opendrive/sumo_signals.hpp"

#include <charconv>
#include <sstream>

#include <fmt/format.h>
#include <pugixml.hpp>

#include "core/errors.hpp"

namespace orch::opendrive {

SumoSignalLinks read_sumo_signal_links(const std::string& net_file) {
  pugi::xml_document doc;
  if (const auto ok = doc.load_file(net_file.c_str()); !ok)
    throw MapError(fmt::format("cannot read the SUMO net {}: {}", net_file, ok.description()));
  SumoSignalLinks out;
  constexpr std::string_view kPrefix = "linkSignalID:";
  for (const pugi::xml_node logic : doc.child("net").children("tlLogic")) {
    const std::string tls = logic.attribute("id").as_string();
    const std::string state = logic.child("phase").attribute("state").as_string();
    int& count = out.link_counts[tls];
    count = std::max(count, static_cast<int>(state.size()));
    for (const pugi::xml_node param : logic.children("param")) {
      const std::string_view key = param.attribute("key").as_string();
      if (key.substr(0, kPrefix.size()) != kPrefix) continue;
      int link = -1;
      const std::string_view index = key.substr(kPrefix.size());
      if (std::from_chars(index.data(), index.data() + index.size(), link).ec != std::errc{} || link < 0) continue;
      std::istringstream ids(param.attribute("value").as_string());
      int order = 0;
      for (std::string id; ids >> id;) out.by_signal[id].push_back({tls, link, order++});
      count = std::max(count, link + 1);
    }
  }
  return out;
}

}  // namespace orch::opendrive
