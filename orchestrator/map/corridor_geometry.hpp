#pragma once
// Geometry the network planner (net_plan.cpp) works with: routes extended straight beyond
// their ends, projections that respect the direction of travel, positions followed along
// a corridor, lane spacing. Internal to map build.
#include <utility>
#include <vector>

#include "core/polyline.hpp"
#include "map/net_plan.hpp"

namespace orch::corridor {

inline constexpr double kExtensionStep = 5.0;   // m; short segments keep Polyline's grid small
inline constexpr double kDirectionChord = 2.0;  // m; end directions from a chord, not one noisy step
// Positions along a corridor are followed in steps of kTrackStep metres, each searched
// within kTrackWindow of where the last step predicts it: a road that comes back near
// itself (a ring, a hairpin) cannot then be mistaken for the stretch being followed.
inline constexpr double kTrackStep = 5.0;
inline constexpr double kTrackWindow = 3 * kTrackStep;

// Unit direction of a line over its first (at_end = false) or last kDirectionChord metres.
Vec2 end_direction(const Polyline& line, bool at_end);

// The line continued straight by `before` metres ahead of its first point and `after`
// metres past its last one. Returns the line and the arc length of its original first point.
std::pair<Polyline, double> extend_straight(const Polyline& line, double before, double after);

// Nearest point of `line` among its stretches heading roughly along `direction` (within
// 60 degrees), so that a road that turns back nearby is not mistaken for this one.
Polyline::Projection project_along(const Polyline& line, const Vec2& p, const Vec2& direction);

// Position along `axis` of every kTrackStep-th metre of `line` (and of its end), followed
// from the middle of `line` outwards.
std::vector<double> track_along(const Polyline& axis, const Polyline& line);

// Mean distance (m) of lane `left` from lane `right`, measured on left's shape.
double lane_spacing(const Polyline& right, const Polyline& left);

// Centre line between an edge's outer lanes (its only lane's shape for one lane).
std::vector<Vec2> centre_line(const PlannedEdge& e);

}  // namespace orch::corridor
