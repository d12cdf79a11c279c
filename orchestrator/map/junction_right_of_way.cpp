#include "map/junction_right_of_way.hpp"

#include <fmt/format.h>
#include <pugixml.hpp>

#include <algorithm>
#include <map>
#include <sstream>

#include "core/errors.hpp"

namespace orch {

namespace {

struct LinkSource {
  std::string from;  // normal edge
  int from_lane = 0;
  std::string state;
};

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Replaces the value of attribute `name` in the element whose text starts at `element` (a
// position in `text`) by `value`, which has the same length.
void replace_attribute(std::string& text, std::size_t element, const std::string& name, const std::string& value) {
  const std::size_t end = text.find('>', element);
  const std::size_t at = text.find(" " + name + "=\"", element);
  if (end == std::string::npos || at == std::string::npos || at > end)
    throw MapError(fmt::format("net: attribute {} not found where expected", name));
  text.replace(at + name.size() + 3, value.size(), value);
}


// Links of one junction that yield to each other in a cycle (A to B, B to C, C to A: netconvert
// 1.15 on a junction that a route passes twice, or whose approaches meet at odd angles, seed
// 449's J0): with a vehicle waiting at each, every one waits for the next for ever, and SUMO
// teleports one after its time-to-teleport. Within each group of links that reach each other
// through yields (a strongly connected component of the "yields to" graph between links from
// different lanes), the links are ranked, the one yielding to the fewest first (the most
// major; then by index), and a link yields only to links ranked before it: a yield to a link
// ranked after it is turned round (that link now yields to it, where the two are foes). The
// graph between groups is left as it is (it has no cycle). Returns whether a bit changed.
template <typename LinkSourceFn>
bool break_yield_cycles(const std::string& junction, const std::vector<std::string>& internal_lanes,
                        std::vector<std::string>& response, const std::vector<std::string>& foes,
                        const LinkSourceFn& link_source, std::vector<bool>& changed_link,
                        std::vector<std::string>& notes) {
  const std::size_t n = response.size();
  const auto bit = [&](const std::vector<std::string>& m, std::size_t i, std::size_t k) {
    return m[i].size() == n && m[i][n - 1 - k] == '1';
  };
  std::vector<std::string> lane(n);
  for (std::size_t i = 0; i < n; ++i) {
    const LinkSource* src = link_source(internal_lanes[i]).second;
    lane[i] = src ? fmt::format("{}_{}", src->from, src->from_lane) : internal_lanes[i];
  }
  const auto edge = [&](std::size_t i, std::size_t k) { return i != k && lane[i] != lane[k] && bit(response, i, k); };
  // Tarjan's strongly connected components.
  std::vector<int> index(n, -1);
  std::vector<int> low(n, 0);
  std::vector<int> component(n, -1);
  std::vector<bool> on_stack(n, false);
  std::vector<std::size_t> stack;
  int next_index = 0;
  int components = 0;
  const auto connect = [&](const auto& self, std::size_t v) -> void {
    index[v] = low[v] = next_index++;
    stack.push_back(v);
    on_stack[v] = true;
    for (std::size_t w = 0; w < n; ++w) {
      if (!edge(v, w)) continue;
      if (index[w] < 0) {
        self(self, w);
        low[v] = std::min(low[v], low[w]);
      } else if (on_stack[w]) {
        low[v] = std::min(low[v], index[w]);
      }
    }
    if (low[v] != index[v]) return;
    for (;;) {
      const std::size_t w = stack.back();
      stack.pop_back();
      on_stack[w] = false;
      component[w] = components;
      if (w == v) break;
    }
    ++components;
  };
  for (std::size_t v = 0; v < n; ++v)
    if (index[v] < 0) connect(connect, v);
  bool changed = false;
  for (int c = 0; c < components; ++c) {
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < n; ++i)
      if (component[i] == c) members.push_back(i);
    if (members.size() < 2) continue;
    const auto yield_count = [&](std::size_t i) { return std::count(response[i].begin(), response[i].end(), '1'); };
    std::stable_sort(members.begin(), members.end(),
                     [&](std::size_t a, std::size_t b) { return yield_count(a) < yield_count(b); });
    std::string order;
    for (std::size_t r = 0; r < members.size(); ++r) {
      order += (order.empty() ? "" : ", ") + internal_lanes[members[r]];
      for (std::size_t q = r + 1; q < members.size(); ++q) {
        const std::size_t first = members[r];
        const std::size_t later = members[q];
        if (!edge(first, later)) continue;
        response[first][n - 1 - later] = '0';
        if (bit(foes, later, first)) response[later][n - 1 - first] = '1';
        changed = changed_link[first] = changed_link[later] = true;
      }
    }
    notes.push_back(fmt::format("junction {}: links {} yielded to each other in a cycle (a deadlock when each has a "
                                "vehicle waiting); they now go in this order",
                                junction, order));
  }
  return changed;
}

}  // namespace

std::string without_mutual_yields(std::string net, std::vector<std::string>& notes) {
  pugi::xml_document doc;
  if (!doc.load_buffer(net.data(), net.size())) return net;  // netconvert's output; the lane map reports it
  // The lane each internal lane (a connection's "via") comes from: a normal lane, or the
  // first internal lane of a link that waits inside the junction (cont="1"), whose second
  // internal lane is the one the junction's intLanes lists.
  std::map<std::string, LinkSource> via_source;
  for (const pugi::xml_node c : doc.child("net").children("connection")) {
    const std::string via = c.attribute("via").value();
    if (!via.empty())
      via_source[via] = {c.attribute("from").value(), c.attribute("fromLane").as_int(), c.attribute("state").value()};
  }
  // The normal lane a link starts from and the internal lane its connection from there goes
  // through (whose connection carries the link's state).
  const auto link_source = [&](std::string via) -> std::pair<std::string, const LinkSource*> {
    for (int step = 0; step < 4; ++step) {
      const auto it = via_source.find(via);
      if (it == via_source.end()) return {via, nullptr};
      if (it->second.from.empty() || it->second.from[0] != ':') return {via, &it->second};
      via = fmt::format("{}_{}", it->second.from, it->second.from_lane);
    }
    return {via, nullptr};
  };
  for (const pugi::xml_node j : doc.child("net").children("junction")) {
    const std::string type = j.attribute("type").value();
    if (type == "internal" || type == "dead_end") continue;
    const std::vector<std::string> internal_lanes = words(j.attribute("intLanes").value());
    std::vector<std::string> response;
    std::vector<std::string> foes;
    for (const pugi::xml_node r : j.children("request")) {
      response.emplace_back(r.attribute("response").value());
      foes.emplace_back(r.attribute("foes").value());
    }
    const std::size_t n = response.size();
    if (n == 0 || internal_lanes.size() != n) continue;  // no internal lanes: not our nets
    bool changed = false;
    std::vector<bool> changed_link(n, false);
    // response[i][n - 1 - k] == '1': link i yields to link k (SUMO writes the bits last link first).
    const auto yields = [&](std::size_t i, std::size_t k) {
      return response[i].size() == n && response[i][n - 1 - k] == '1';
    };
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!yields(a, b) || !yields(b, a)) continue;
        const LinkSource* sa = link_source(internal_lanes[a]).second;
        const LinkSource* sb = link_source(internal_lanes[b]).second;
        if (!sa || !sb || sa->from != sb->from || sa->from_lane == sb->from_lane)
          continue;  // only the lane-level rule between lanes of one edge is resolved here
        const bool a_right = sa->from_lane < sb->from_lane;
        const std::size_t go = a_right ? a : b;
        const std::size_t wait = a_right ? b : a;
        response[go][n - 1 - wait] = '0';
        changed = changed_link[go] = true;
        notes.push_back(fmt::format(
            "junction {}: the connections from lanes {} and {} of edge \"{}\" cross and netconvert made each yield "
            "to the other; lane {} (the right one) goes first",
            j.attribute("id").value(), sa->from_lane, sb->from_lane, sa->from, (a_right ? sa : sb)->from_lane));
      }
    // Only on priority junctions: a traffic light's phases keep links of a cycle apart, and
    // right_before_left / allway_stop junctions are cyclic by design (SUMO's own rules there).
    if (type == "priority")
      changed = break_yield_cycles(j.attribute("id").value(), internal_lanes, response, foes, link_source, changed_link,
                                   notes) || changed;
    if (!changed) continue;
    const std::size_t junction_at = net.find(fmt::format("<junction id=\"{}\" ", j.attribute("id").value()));
    if (junction_at == std::string::npos) throw MapError("net: junction not found where expected");
    for (std::size_t i = 0; i < n; ++i) {
      if (!changed_link[i]) continue;
      const std::size_t request_at = net.find(fmt::format("<request index=\"{}\"", i), junction_at);
      if (request_at == std::string::npos) throw MapError("net: request not found where expected");
      replace_attribute(net, request_at, "response", response[i]);
      const auto [first_via, source] = link_source(internal_lanes[i]);
      if (!source || response[i].find('1') != std::string::npos || source->state != "m") continue;
      const std::size_t connection_at = net.find(fmt::format(" via=\"{}\"", first_via));
      const std::size_t element = net.rfind("<connection ", connection_at);
      if (connection_at == std::string::npos || element == std::string::npos)
        throw MapError("net: connection not found where expected");
      replace_attribute(net, element, "state", "M");
    }
  }
  return net;
}

}  // namespace orch
