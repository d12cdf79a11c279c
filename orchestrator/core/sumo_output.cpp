#include "core/sumo_output.hpp"

namespace orch {

std::string without_generation_date(std::string net) {
  const std::string marker = "<!-- generated on ";
  const auto start = net.find(marker);
  if (start == std::string::npos) return net;
  const auto by = net.find(" by ", start);
  const auto eol = net.find('\n', start);
  if (by == std::string::npos || (eol != std::string::npos && by > eol)) return net;
  net.replace(start, by - start, "<!-- generated");
  return net;
}

}  // namespace orch
