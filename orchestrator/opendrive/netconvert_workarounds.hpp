#pragma once
// OpenDRIVE content that netconvert 1.15 refuses although the standard allows it, rewritten in
// the copy netconvert reads (never in the user's file, never in the geometry the runtime uses):
//  - a <signal> with an empty `type` (netconvert: "Attribute 'type' in definition of signal
//    ... is empty", then quits): dropped. The runtime reads no signals; SUMO only loses a sign.
//  - a direct junction (<junction type="direct">, OpenDRIVE 1.7: roads joined without
//    connecting roads; netconvert: "Attribute 'connectingRoad' is missing"): the junction goes,
//    the roads' links to it become road-to-road links. SUMO joins a road end to one other road
//    only, so the linked road's end keeps its first connection's incoming road; the other
//    incoming roads end there in SUMO (scripted entities still follow the OpenDRIVE lanes; a
//    vehicle SUMO drives cannot take those connections).
// Each rewrite is a warning naming the .xodr file, line and element.
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "core/diagnostics.hpp"

namespace orch::xml {
class XmlSource;
}

namespace orch::opendrive {

// Rewrites `source`'s document in place; returns what was rewritten, as warnings.
std::vector<Diagnostic> apply_netconvert_workarounds(const xml::XmlSource& source);

}  // namespace orch::opendrive
