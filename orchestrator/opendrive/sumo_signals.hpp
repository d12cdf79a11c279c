#pragma once
// The OpenDRIVE signals netconvert turned into SUMO traffic lights: netconvert gives each
// traffic light (tlLogic) one parameter per controlled link, "linkSignalID:<link index>",
// whose value lists the ids of the OpenDRIVE signals that control the link. An OpenDRIVE
// signal netconvert made no traffic light of (no junction after it, a static sign) is in no list.
#include <map>
#include <string>
#include <vector>

namespace orch::opendrive {

struct SumoSignalLink {
  std::string tls;  // the SUMO traffic light's id
  int link = 0;     // the index of the link in its state string
  int order = 0;    // the signal's place in the link's list (netconvert's order)
};

struct SumoSignalLinks {
  std::map<std::string, std::vector<SumoSignalLink>> by_signal;  // OpenDRIVE signal id -> its links
  std::map<std::string, int> link_counts;                         // tls id -> links (state length)
};

// Reads `net_file`'s traffic lights. Throws MapError when the file cannot be read.
SumoSignalLinks read_sumo_signal_links(const std::string& net_file);

}  // namespace orch::opendrive
