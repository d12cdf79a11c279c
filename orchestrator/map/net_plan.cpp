#include "map/net_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "core/checked_numeric.hpp"
#include "core/errors.hpp"
#include "map/corridor_cut_error.hpp"
#include "map/corridor_geometry.hpp"
#include "map/corridor_member.hpp"
#include "map/corridor_names.hpp"
#include "map/junction_shape.hpp"
#include "map/route_corridors.hpp"

namespace orch {

namespace {

using namespace corridor;

// Consecutive routes of one lane may share up to this much road (a repeated point or two).
constexpr double kMaxContinuationOverlap = 2.0;  // m

// m a lane ending at a junction may reach straight beyond its route's end to the junction's cut.
// It was 0.5 m (at most 2.5 cm off a 5 m radius). A shared lane's best fit (junction_pieces.cpp)
// fits its routes within kPlannedLaneMiss where it runs, not before its start, where they are
// still converging into it: seed 239's lane of three routes reached 0.46 m back to its
// neighbour's cut, 0.108 m beside the third route's waypoint there (the best fit had moved the
// lane's start). 0.3 m, not less: at 0.2 m seed 114's junction J4 took another shape and a
// route broke there (not traced further).
constexpr double kMaxJunctionExtension = 0.3;

// Cut::member of a cut that only limits the length of edges (no lane ends there).
constexpr std::size_t kNoMember = std::numeric_limits<std::size_t>::max();

struct Cut {
  Vec2 point;
  Vec2 direction;
  double key = 0;            // position along the corridor
  std::size_t member = 0;    // the lane end that placed the cut (kNoMember: a length cut)
  bool at_start = false;     // ... its start (else its end)
  std::string node;          // the junction at this cut ("" = a node of the corridor's own)
};

struct Event {
  double key = 0;  // position along the corridor's reference route
  std::size_t member = 0;
  bool is_start = false;
  std::string node;  // the junction this lane end lies at ("" = a free end)
};

class CorridorPlanner {
 public:
  CorridorPlanner(const WaypointFile& wf, const std::vector<std::size_t>& route_indices, const NetPlanSettings& st,
                  const std::vector<CorridorLine>* info)
      : settings_(st), info_given_(info != nullptr) {
    double shortest = std::numeric_limits<double>::infinity();
    for (std::size_t i : route_indices)
      shortest = std::min(shortest, wf.routes[i].line.length() + 2 * st.lane_extension);
    merge_ = std::min(kMaxCutMerge, 0.5 * shortest);
    slack_ = merge_ + kExtensionStep;
    for (std::size_t i : route_indices) {
      Member m;
      m.route = &wf.routes[i];
      m.index = i;
      const double ext = st.lane_extension + slack_;
      std::tie(m.line, m.first_wp_s) = extend_straight(m.route->line, ext, ext);
      if (info) m.info = &(*info)[i];
      // A lane that ends at a junction ends exactly there: the junction's internal lanes go on.
      const auto reach = [&](bool start) {
        if (!m.end_node(start).empty()) return 0.0;
        const double limit = m.info ? (start ? m.info->start_extension : m.info->end_extension) : -1.0;
        return limit < 0 ? st.lane_extension : std::min(limit, st.lane_extension);
      };
      m.lane_start = m.first_wp_s - reach(true);
      m.lane_end = m.first_wp_s + m.route->line.length() + reach(false);
      members_.push_back(std::move(m));
    }
  }

  void plan(std::set<std::string>& used_names, NetPlan& out) {
    const std::size_t first_edge = out.edges.size();
    build_axis();
    std::vector<NamedRoute> named;
    for (const Member& m : members_) named.push_back({m.lateral, m.index, m.route->id});
    name_ = corridor_name(std::move(named), used_names);
    link_continuations(out.notes);
    place_cuts();
    while (const std::size_t c = cut_members()) {
      // A free end's straight extension that leaves its neighbours (a route ending in the
      // middle of a turn beside another: seed 190) has its foot on them out of order with
      // their own lane ends. That lane ends at its route's last (first) waypoint instead,
      // and the cuts are placed again; anything else is refused.
      if (!drop_free_extension(c)) cut_members(true);
      for (Member& m : members_) m.cut_s.clear();
      cuts_.clear();
      place_cuts();
    }
    std::vector<std::ptrdiff_t> edge_of_segment(cuts_.size() - 1, -1);
    std::vector<bool> node_used(cuts_.size(), false);
    int edge_number = 0;
    for (std::size_t seg = 0; seg + 1 < cuts_.size(); ++seg) {
      PlannedEdge e = plan_edge(seg, out.notes);
      if (e.lanes.empty()) continue;  // the corridor's routes leave a gap here
      e.id = fmt::format("{}#{}", name_, edge_number++);
      e.from = node_id(seg);
      e.to = node_id(seg + 1);
      if (info_given_) e.priority = static_cast<int>(e.lanes.size());
      node_used[seg] = node_used[seg + 1] = true;
      edge_of_segment[seg] = static_cast<std::ptrdiff_t>(out.edges.size());
      out.edges.push_back(std::move(e));
    }
    std::vector<PlannedNode> nodes;
    for (std::size_t c = 0; c < cuts_.size(); ++c)
      if (node_used[c] && cuts_[c].node.empty()) nodes.push_back(plan_node(c, edge_of_segment, out.edges));
    for (std::size_t i = first_edge; i < out.edges.size(); ++i) {
      PlannedEdge& e = out.edges[i];
      e.shape = centre_line(e);
      for (const PlannedNode& n : nodes) {
        if (n.id == e.from) e.shape.front() = n.position;
        if (n.id == e.to) e.shape.back() = n.position;
      }
    }
    out.nodes.insert(out.nodes.end(), nodes.begin(), nodes.end());
    add_connections(edge_of_segment, out);
  }

 private:
  // The longest route, extended far enough that every other member projects onto it: the
  // common measure of "how far along the corridor" for ordering the cuts.
  void build_axis() {
    std::size_t ref = 0;
    double longest = 0;
    for (std::size_t i = 0; i < members_.size(); ++i)
      if (members_[i].route->line.length() > longest) {
        longest = members_[i].route->line.length();
        ref = i;
      }
    double reach = 0;
    for (const Member& m : members_) reach = std::max(reach, m.line.length());
    axis_ = extend_straight(members_[ref].route->line, reach, reach).first;
    for (Member& m : members_) {
      m.keys = track_along(axis_, m.line);
      const double mid = m.first_wp_s + m.route->line.length() / 2;
      m.lateral = axis_.project_near(m.line.point_at(mid), m.key_of(mid), kTrackWindow).lateral;
    }
  }

  // Every lane start and end is an event; events closer than merge_ become one cut, placed
  // so that no lane loses its extension where possible (earliest start, latest end).
  void place_cuts() {
    std::vector<Event> events;
    for (std::size_t i = 0; i < members_.size(); ++i) {
      const Member& m = members_[i];
      for (const bool start : {true, false}) {
        events.push_back({m.key_of(start ? m.lane_start : m.lane_end), i, start, m.end_node(start)});
      }
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
      if (a.key != b.key) return a.key < b.key;
      if (a.member != b.member) return a.member < b.member;
      return a.is_start > b.is_start;
    });
    std::vector<bool> open(members_.size(), false);  // lanes running at the current cut
    for (std::size_t first = 0; first < events.size();) {
      std::size_t last = first;
      // Lane ends at one junction are one cut; they never merge with other lane ends, nor
      // with the other end of a lane in the group (a short lane that leaves a junction and
      // comes back to it keeps both its ends).
      std::set<std::size_t> in_group{events[first].member};
      while (last + 1 < events.size() && events[last + 1].key - events[first].key <= merge_ &&
             events[last + 1].node == events[first].node && !in_group.count(events[last + 1].member))
        in_group.insert(events[++last].member);
      bool all_start = true;
      bool all_end = true;
      for (std::size_t k = first; k <= last; ++k) {
        all_start = all_start && events[k].is_start;
        all_end = all_end && !events[k].is_start;
      }
      const Event& rep = all_start ? events[first] : all_end ? events[last] : events[(first + last) / 2];
      // An edge cannot lead from a junction back to itself: such a stretch gets a cut of its own in the middle.
      add_length_cuts(rep.key, open, !rep.node.empty() && !cuts_.empty() && cuts_.back().node == rep.node);
      for (std::size_t k = first; k <= last; ++k) {
        Member& m = members_[events[k].member];
        (events[k].is_start ? m.start_cut : m.end_cut) = cuts_.size();
      }
      const Member& rm = members_[rep.member];
      const double s = rep.is_start ? rm.lane_start : rm.lane_end;
      cuts_.push_back({rm.line.point_at(s), rm.line.tangent_at(s), rep.key, rep.member, rep.is_start, rep.node});
      for (std::size_t k = first; k <= last; ++k) open[events[k].member] = events[k].is_start;
      first = last + 1;
    }
  }

  // Cuts that split the stretch from the last cut to `key` into equal pieces no longer than
  // max_edge_length, placed on the first lane running there (the other lanes are cut at
  // the feet of that point, like at any cut). None across a gap without lanes.
  void add_length_cuts(double key, const std::vector<bool>& open, bool split = false) {
    if ((settings_.max_edge_length <= 0 && !split) || cuts_.empty()) return;
    const auto on = std::find(open.begin(), open.end(), true);
    if (on == open.end()) return;
    const std::size_t ref = static_cast<std::size_t>(on - open.begin());
    const double from = cuts_.back().key;
    int pieces = settings_.max_edge_length <= 0
                     ? 1
                     : clamped_ceil<int>((key - from) / settings_.max_edge_length - 1e-9, 0, 1 << 30);
    if (split) pieces = std::max(pieces, 2);
    for (int j = 1; j < pieces; ++j) {
      const double k = from + (key - from) * j / pieces;
      const double s = members_[ref].s_of_key(k);
      cuts_.push_back({members_[ref].line.point_at(s), members_[ref].line.tangent_at(s), k, kNoMember, false, {}});
    }
  }

  // Where each member crosses each cut it spans: exactly at its own lane ends, elsewhere
  // the foot of the cut point on it, searched near where the tracking predicts it. Returns
  // 0, or the cut that would cut a member out of order (refused when `refuse`).
  std::size_t cut_members(bool refuse = false) {
    for (std::size_t i = 0; i < members_.size(); ++i) {
      Member& m = members_[i];
      if (m.end_cut <= m.start_cut)
        throw MapError(fmt::format("route \"{}\" is too short to become a lane", m.route->id));
      for (std::size_t c = m.start_cut; c <= m.end_cut; ++c) {
        const Cut& cut = cuts_[c];
        double s = m.line.project_near(cut.point, m.s_of_key(cut.key), kTrackWindow).s;
        if (cut.member == i) s = cut.at_start ? m.lane_start : m.lane_end;
        // A lane never ends before its route's last waypoint (nor starts after its first).
        // The foot of a neighbour's lane end 3-7 m across lands on this route's last
        // segment, and that segment may be drawing noise tilted 2-12 degrees: the foot
        // then lies 0.2-0.3 m short of the route's end (seeds 171, 257: routes ending
        // together at the map's edge, the lane 0.18 m short of the last waypoint).
        if (c == m.end_cut) s = std::max(s, m.last_wp_s());
        if (c == m.start_cut) s = std::min(s, m.first_wp_s);
        s = std::clamp(s, 0.0, m.line.length());
        if (!m.cut_s.empty() && s <= m.cut_s.back() + 0.5) {
          if (!refuse) return c;
          throw CorridorCutError(fmt::format("cannot cut route \"{}\" consistently with its neighbouring routes near "
                                             "({:.1f}, {:.1f}): its neighbours start or end out of order along it",
                                             m.route->id, cut.point.x(), cut.point.y()),
                                 m.index, cut.point);
        }
        m.cut_s.push_back(s);
      }
      keep_junction_ends_drawn(m);
    }
    return 0;
  }

  // The member lane end that placed cut c, or the one before it, when it is a free end
  // extended straight past its route's waypoint: that extension goes. Whether one went.
  bool drop_free_extension(std::size_t c) {
    for (const std::size_t k : {c, c - 1}) {
      if (k >= cuts_.size() || cuts_[k].member == kNoMember) continue;
      Member& m = members_[cuts_[k].member];
      const bool start = cuts_[k].at_start;
      if (!m.end_node(start).empty()) continue;
      double& lane = start ? m.lane_start : m.lane_end;
      const double wp = start ? m.first_wp_s : m.last_wp_s();
      if (std::abs(lane - wp) < 1e-9) continue;
      lane = wp;
      return true;
    }
    return false;
  }

  // A lane ending at a junction whose cut lies beyond its end (the cut placed at a neighbour's
  // lane end further out) would reach there along its straight extension, off the route where
  // the route curves into the junction (seed 9: 1.6 m straight, 0.14 m beside the route). It
  // ends at its own end instead; the junction's internal lane follows the route's points from
  // there. Extensions up to kMaxJunctionExtension stay.
  static void keep_junction_ends_drawn(Member& m) {
    if (m.cut_s.size() < 2) return;
    if (!m.end_node(true).empty() && m.cut_s.front() < m.lane_start - kMaxJunctionExtension &&
        m.lane_start < m.cut_s[1] - 0.5)
      m.cut_s.front() = m.lane_start;
    if (!m.end_node(false).empty() && m.cut_s.back() > m.lane_end + kMaxJunctionExtension &&
        m.lane_end > m.cut_s[m.cut_s.size() - 2] + 0.5)
      m.cut_s.back() = m.lane_end;
  }

  [[nodiscard]] PlannedEdge plan_edge(std::size_t seg, std::vector<std::string>& notes) const {
    std::vector<const Member*> active;
    for (const Member& m : members_)
      if (m.active_in(seg)) active.push_back(&m);
    PlannedEdge e;
    if (active.empty()) return e;
    std::vector<std::pair<double, PlannedLane>> lanes;
    for (const Member* m : active) {
      const double s0 = m->cut_at(seg);
      const double s1 = m->cut_at(seg + 1);
      PlannedLane lane;
      lane.route_id = m->info ? m->info->routes.front() : m->route->id;
      if (m->info) lane.routes = m->info->routes;
      lane.piece = static_cast<int>(m->index);
      lane.shape = m->line.slice(s0, s1).simplified(settings_.simplify_tolerance);
      lane.speed = lane_speed(*m, s0, s1, notes);
      lanes.emplace_back(0.0, std::move(lane));
    }
    // Order right to left by the lateral offset from the longest lane of the stretch.
    const auto ref = std::max_element(lanes.begin(), lanes.end(), [](const auto& a, const auto& b) {
      return a.second.shape.length() < b.second.shape.length();
    });
    const Polyline ref_shape = ref->second.shape;
    for (auto& [lateral, lane] : lanes) {
      const double mid = lane.shape.length() / 2;
      lateral = project_along(ref_shape, lane.shape.point_at(mid), lane.shape.tangent_at(mid)).lateral;
    }
    std::stable_sort(lanes.begin(), lanes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& l : lanes) e.lanes.push_back(std::move(l.second));
    // Lane width = spacing of neighbouring routes (mean of both sides for inner lanes).
    std::vector<double> spacing;
    for (std::size_t i = 0; i + 1 < e.lanes.size(); ++i)
      spacing.push_back(lane_spacing(e.lanes[i].shape, e.lanes[i + 1].shape));
    for (std::size_t i = 0; i < e.lanes.size(); ++i) {
      std::vector<double> sides;
      if (i > 0) sides.push_back(spacing[i - 1]);
      if (i < spacing.size()) sides.push_back(spacing[i]);
      double width = kDefaultLaneWidth;
      if (!sides.empty()) width = (sides.front() + sides.back()) / 2;
      e.lanes[i].width = std::round(width * 100) / 100;
    }
    return e;
  }

  // The junction at a cut: a line across the road through the ends of every lane that
  // ends or begins there (see PlannedNode::shape), reaching half a lane beyond the outer
  // ones. Each piece is perpendicular to the lanes it touches (the other lanes' ends are
  // feet of the cut point on them), so no lane crosses it anywhere but at its own end,
  // however the road curves.
  [[nodiscard]] PlannedNode plan_node(std::size_t c, const std::vector<std::ptrdiff_t>& edge_of_segment,
                                      const std::vector<PlannedEdge>& edges) const {
    const Vec2 n = left_normal(cuts_[c].direction);
    struct CutLaneEnd {
      double lateral;
      Vec2 point;
      Vec2 normal;  // left normal of the lane there
    };
    std::vector<CutLaneEnd> ends;
    for (const Member& m : members_) {
      if (m.start_cut > c || m.end_cut < c) continue;
      const double s = m.cut_at(c);
      const Vec2 p = m.line.point_at(s);
      ends.push_back({p.dot(n), p, left_normal(m.line.tangent_at(s))});
    }
    std::sort(ends.begin(), ends.end(), [](const CutLaneEnd& a, const CutLaneEnd& b) { return a.lateral < b.lateral; });
    double half_width = 0;
    for (const std::size_t seg : {c - 1, c}) {
      if (seg >= edge_of_segment.size() || edge_of_segment[seg] < 0) continue;
      for (const PlannedLane& l : edges[static_cast<std::size_t>(edge_of_segment[seg])].lanes)
        half_width = std::max(half_width, l.width / 2);
    }
    PlannedNode node;
    node.id = node_id(c);
    node.position = 0.5 * (ends.front().point + ends.back().point);
    // Out through the lane ends and back the same way: netconvert closes the shape into a
    // polygon, and a closing chord straight across a curved cut would clip the lanes.
    node.shape.push_back(ends.front().point - half_width * ends.front().normal);
    for (const CutLaneEnd& e : ends) node.shape.push_back(e.point);
    node.shape.push_back(ends.back().point + half_width * ends.back().normal);
    for (auto e = ends.rbegin(); e != ends.rend(); ++e) node.shape.push_back(e->point);
    // Lanes ending far apart (a free end where one lane turns away beside one going straight
    // on, seed 246): the line across their ends runs along the turning lane, and netconvert
    // would cut it there (13.7 m). A tree with no area through the lane ends cuts none.
    std::vector<LaneEnd> lane_ends;
    std::vector<TreeNode> tree;
    for (const std::size_t seg : {c - 1, c}) {
      if (seg >= edge_of_segment.size() || edge_of_segment[seg] < 0) continue;
      for (const PlannedLane& l : edges[static_cast<std::size_t>(edge_of_segment[seg])].lanes) {
        lane_ends.push_back({&l.shape, seg + 1 == c});
        tree.push_back({seg + 1 == c ? l.shape.points().back() : l.shape.point(0), {}});
      }
    }
    if (lane_ends.size() > 1 && cut_length(node.shape, lane_ends) > 0) {
      tree.push_back({node.position, {}});
      if (std::vector<Vec2> t = uncut_tree(tree, lane_ends); !t.empty() && cut_length(t, lane_ends) == 0)
        node.shape = std::move(t);
    }
    return node;
  }

  // Each route continues on its own lane across a cut, and only there.
  void add_connections(const std::vector<std::ptrdiff_t>& edge_of_segment, NetPlan& out) const {
    const auto lane_of = [&](const PlannedEdge& e, const Member& m) {
      for (std::size_t i = 0; i < e.lanes.size(); ++i)
        if (e.lanes[i].piece == static_cast<int>(m.index)) return static_cast<int>(i);
      return -1;
    };
    for (std::size_t c = 1; c + 1 < cuts_.size(); ++c) {
      if (edge_of_segment[c - 1] < 0 || edge_of_segment[c] < 0) continue;
      const PlannedEdge& from = out.edges[static_cast<std::size_t>(edge_of_segment[c - 1])];
      const PlannedEdge& to = out.edges[static_cast<std::size_t>(edge_of_segment[c])];
      for (const Member& m : members_)
        if (m.active_in(c - 1) && m.active_in(c)) out.connections.push_back({from.id, to.id, lane_of(from, m), lane_of(to, m), {}});
      for (const auto& [before, after] : continuations_) {
        const Member& b = members_[before];
        const Member& a = members_[after];
        if (b.end_cut == c && a.start_cut == c) out.connections.push_back({from.id, to.id, lane_of(from, b), lane_of(to, a), {}});
      }
    }
  }

  // One lane drawn as consecutive routes ("B" up to some point, "C" from there on): their
  // extensions would overlap and stack two lanes on each other. Instead both stop halfway
  // between B's last and C's first waypoint, and B's lane continues into C's.
  void link_continuations(std::vector<std::string>& notes) {
    std::vector<bool> has_next(members_.size(), false);
    std::vector<bool> has_previous(members_.size(), false);
    for (std::size_t b = 0; b < members_.size(); ++b)
      for (std::size_t a = 0; a < members_.size(); ++a) {
        Member& before = members_[b];
        Member& after = members_[a];
        if (a == b || has_next[b] || has_previous[a] || std::abs(before.lateral - after.lateral) >= kMinLaneSpacing)
          continue;
        if (!before.end_node(false).empty() || !after.end_node(true).empty()) continue;  // junction ends
        const double end_key = before.key_of(before.last_wp_s());
        const double start_key = after.key_of(after.first_wp_s);
        const double gap = start_key - end_key;
        // Touching or apart by less than the two extensions; overlapping pieces are
        // "coincident" routes and never share a corridor (route_corridors.cpp).
        if (gap < -kMaxContinuationOverlap || gap > 2 * settings_.lane_extension) continue;
        const double meet = (end_key + start_key) / 2;
        before.lane_end = std::max(before.s_of_key(meet), before.last_wp_s());
        after.lane_start = std::min(after.s_of_key(meet), after.first_wp_s);
        has_next[b] = has_previous[a] = true;
        continuations_.emplace_back(b, a);
        notes.push_back(fmt::format("route \"{}\" continues route \"{}\" on the same lane: their lanes are connected",
                                    after.route->id, before.route->id));
      }
  }

  [[nodiscard]] std::string node_id(std::size_t cut) const {
    return cuts_[cut].node.empty() ? fmt::format("{}@{}", name_, cut) : cuts_[cut].node;
  }

  NetPlanSettings settings_;
  bool info_given_ = false;
  double merge_ = kMaxCutMerge;
  double slack_ = kMaxCutMerge;
  std::vector<Member> members_;
  Polyline axis_;
  std::vector<Cut> cuts_;
  std::vector<std::pair<std::size_t, std::size_t>> continuations_;  // (before, after) member indices
  std::string name_;
};

}  // namespace

void plan_corridors(const WaypointFile& lines, const std::vector<CorridorLine>* info, const NetPlanSettings& settings,
                    NetPlan& out) {
  std::vector<bool> solitary;
  if (info)
    for (const CorridorLine& l : *info) solitary.push_back(l.solitary);
  const auto corridors = find_corridors(lines, out.notes, solitary);
  out.corridors += static_cast<int>(corridors.size());
  std::set<std::string> used_names;
  for (const auto& corridor : corridors) CorridorPlanner(lines, corridor, settings, info).plan(used_names, out);
  // Remarks repeat per stretch of road; keep the first of each.
  std::vector<std::string> unique_notes;
  for (auto& note : out.notes)
    if (std::find(unique_notes.begin(), unique_notes.end(), note) == unique_notes.end()) unique_notes.push_back(std::move(note));
  out.notes = std::move(unique_notes);
}

}  // namespace orch
