#include "run/traffic_area.hpp"

#include <algorithm>

namespace orch {

std::vector<AreaPart> area_parts(const openscenario::TrafficAreaRoadRange& range,
                                 const std::vector<double>& cursor_road_lengths) {
  std::vector<AreaPart> parts;
  for (std::size_t i = 0; i + 1 < range.cursors.size(); ++i) {
    const auto& a = range.cursors[i];
    const auto& b = range.cursors[i + 1];
    const double a_length = cursor_road_lengths[i], b_length = cursor_road_lengths[i + 1];
    if (a.road == b.road) {
      // A cursor without s: its road's start when it opens the range, else its end.
      const double sa = std::clamp(a.s.value_or(i == 0 ? 0.0 : a_length), 0.0, a_length);
      const double sb = std::clamp(b.s.value_or(a_length), 0.0, a_length);
      parts.push_back({a.road, std::min(sa, sb), std::max(sa, sb), a.lanes.empty() ? b.lanes : a.lanes});
    } else {
      if (i == 0 || range.cursors[i - 1].road != a.road)  // a's road from its cursor on (not covered yet)
        parts.push_back({a.road, std::clamp(a.s.value_or(0.0), 0.0, a_length), a_length, a.lanes});
      parts.push_back({b.road, 0.0, std::clamp(b.s.value_or(b_length), 0.0, b_length), b.lanes});
    }
  }
  if (range.length) {  // the range ends `length` m after its first cursor
    double left = *range.length;
    std::vector<AreaPart> kept;
    for (AreaPart& p : parts) {
      if (left <= 0) break;
      p.to = std::min(p.to, p.from + left);
      left -= p.to - p.from;
      kept.push_back(std::move(p));
    }
    parts = std::move(kept);
  }
  return parts;
}

bool in_parts(const AreaPlace& place, const std::vector<AreaPart>& parts) {
  for (const AreaPart& p : parts)
    if (p.road == place.road && place.s >= p.from - 1e-9 && place.s <= p.to + 1e-9 &&
        (p.lanes.empty() || std::find(p.lanes.begin(), p.lanes.end(), place.lane) != p.lanes.end()))
      return true;
  return false;
}

}  // namespace orch
