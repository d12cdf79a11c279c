#include "core/scenario_format.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>

namespace orch {
namespace {

// The name of the first element of an XML text: skips the declaration, comments,
// processing instructions and a DOCTYPE.
std::string root_element(const std::string& text, std::size_t pos) {
  while ((pos = text.find('<', pos)) != std::string::npos) {
    if (text.compare(pos, 4, "<!--") == 0) {
      pos = text.find("-->", pos);
      if (pos == std::string::npos) return "";
      continue;
    }
    if (text.compare(pos, 2, "<?") == 0 || text.compare(pos, 2, "<!") == 0) {
      ++pos;
      continue;
    }
    std::size_t end = pos + 1;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_' ||
                                 text[end] == ':' || text[end] == '-' || text[end] == '.'))
      ++end;
    return text.substr(pos + 1, end - pos - 1);
  }
  return "";
}

}  // namespace

ScenarioFormat detect_scenario_format(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::size_t pos = head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (pos < head.size() && std::isspace(static_cast<unsigned char>(head[pos]))) ++pos;
  if (pos < head.size() && head[pos] == '{') return ScenarioFormat::ScenarioExecutorJson;
  if (pos < head.size() && head[pos] == '<')
    return root_element(head, pos) == "OpenSCENARIO" ? ScenarioFormat::OpenScenario : ScenarioFormat::Unknown;
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".json") return ScenarioFormat::ScenarioExecutorJson;
  if (extension == ".xosc") return ScenarioFormat::OpenScenario;
  return ScenarioFormat::Unknown;
}

}  // namespace orch
