#include "map/corridor_names.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

#include "map/route_corridors.hpp"

namespace orch {

namespace {
constexpr std::size_t kMaxNameLength = 60;
}  // namespace

std::string sumo_safe_id(const std::string& id) {
  std::string out = id.empty() ? std::string("route") : id;
  for (char& c : out)
    if (std::string_view(" \t\n\r|\\'\";,<>&").find(c) != std::string_view::npos) c = '_';
  if (out.front() == ':') out.front() = '_';  // a leading ':' marks SUMO's internal edges
  return out;
}

std::string corridor_name(std::vector<NamedRoute> routes, std::set<std::string>& used) {
  std::stable_sort(routes.begin(), routes.end(), [](const NamedRoute& a, const NamedRoute& b) { return a.lateral < b.lateral; });
  // Pieces of one lane (consecutive routes) keep their file order.
  for (auto run = routes.begin(); run != routes.end();) {
    auto end = run + 1;
    while (end != routes.end() && end->lateral - (end - 1)->lateral < kMinLaneSpacing / 2) ++end;
    std::sort(run, end, [](const NamedRoute& a, const NamedRoute& b) { return a.index < b.index; });
    run = end;
  }
  std::string name;
  for (const NamedRoute& r : routes) name += (name.empty() ? "" : "+") + sumo_safe_id(r.id);
  if (name.size() > kMaxNameLength) name = sumo_safe_id(routes.front().id) + ".." + sumo_safe_id(routes.back().id);
  std::string unique = name;
  for (int k = 2; used.count(unique); ++k) unique = fmt::format("{}~{}", name, k);
  used.insert(unique);
  return unique;
}

}  // namespace orch
