#include "opendrive/netconvert_workarounds.hpp"

#include <map>
#include <string>

#include <fmt/format.h>

#include "xml/xml_source.hpp"

namespace orch::opendrive {

namespace {

Diagnostic warning(const xml::XmlSource& source, const pugi::xml_node& node, std::string message) {
  return Diagnostic{Severity::Warning, source.where(node), std::move(message)};
}

void drop_signals_without_type(const xml::XmlSource& source, std::vector<Diagnostic>& out) {
  for (pugi::xml_node road : source.root().children("road")) {
    pugi::xml_node signals = road.child("signals");
    for (pugi::xml_node signal = signals.child("signal"); signal;) {
      const pugi::xml_node next = signal.next_sibling("signal");
      if (std::string(signal.attribute("type").as_string("")).empty()) {
        out.push_back(warning(source, signal,
                              fmt::format("signal {} of road {} has no type: netconvert cannot read it, so the "
                                          "SUMO net is built without it (the standard allows it; the run does not "
                                          "use signals)",
                                          signal.attribute("id").as_string("?"), road.attribute("id").as_string("?"))));
        signals.remove_child(signal);
      }
      signal = next;
    }
  }
}

// The link element (predecessor or successor) of `road` that names junction `junction`.
pugi::xml_node link_to_junction(pugi::xml_node road, const std::string& junction) {
  for (pugi::xml_node end : road.child("link").children())
    if (std::string(end.attribute("elementType").as_string("")) == "junction" &&
        junction == end.attribute("elementId").as_string(""))
      return end;
  return {};
}

void set_road_link(pugi::xml_node end, const std::string& road, const std::string& contact) {
  end.attribute("elementType").set_value("road");
  end.attribute("elementId").set_value(road.c_str());
  if (!end.attribute("contactPoint")) end.append_attribute("contactPoint");
  end.attribute("contactPoint").set_value(contact.c_str());
}

void replace_direct_junctions(const xml::XmlSource& source, std::vector<Diagnostic>& out) {
  std::map<std::string, pugi::xml_node> roads;
  for (pugi::xml_node road : source.root().children("road")) roads.emplace(road.attribute("id").as_string(""), road);
  for (pugi::xml_node junction = source.root().child("junction"); junction;) {
    const pugi::xml_node next = junction.next_sibling("junction");
    if (std::string(junction.attribute("type").as_string("")) != "direct") {
      junction = next;
      continue;
    }
    const std::string id = junction.attribute("id").as_string("");
    std::string kept;
    for (pugi::xml_node connection : junction.children("connection")) {
      const auto incoming = roads.find(connection.attribute("incomingRoad").as_string(""));
      const auto linked = roads.find(connection.attribute("linkedRoad").as_string(""));
      if (incoming == roads.end() || linked == roads.end()) continue;  // the reader reports bad references
      const std::string contact = connection.attribute("contactPoint").as_string("start");
      // The incoming road's end at the junction: the end whose link names it.
      if (pugi::xml_node end = link_to_junction(incoming->second, id)) {
        const bool incoming_end = std::string(end.name()) == "successor";
        set_road_link(end, linked->first, contact);
        if (pugi::xml_node back = link_to_junction(linked->second, id)) {
          set_road_link(back, incoming->first, incoming_end ? "end" : "start");
          kept = incoming->first;
        }
      }
    }
    out.push_back(warning(source, junction,
                          fmt::format("direct junction {} (OpenDRIVE 1.7): netconvert cannot read it, so the SUMO "
                                      "net joins its roads by road links{}; the other connections end in SUMO "
                                      "(entities the storyboard moves still follow the OpenDRIVE lanes)",
                                      id, kept.empty() ? "" : fmt::format(" (the linked road's end to road {})", kept))));
    source.root().remove_child(junction);
    junction = next;
  }
}

}  // namespace

std::vector<Diagnostic> apply_netconvert_workarounds(const xml::XmlSource& source) {
  std::vector<Diagnostic> out;
  drop_signals_without_type(source, out);
  replace_direct_junctions(source, out);
  return out;
}

}  // namespace orch::opendrive
