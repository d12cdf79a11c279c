#pragma once
// Text for XML attribute values in the SUMO files the orchestrator generates (plain net
// XML, route files): ids come from users' waypoint files and may hold any character.
#include <string>
#include <string_view>

namespace orch {

inline std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace orch
