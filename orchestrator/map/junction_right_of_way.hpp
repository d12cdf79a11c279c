#pragma once
// Right of way that netconvert 1.15 leaves deadlocked: two lanes of one road whose connections
// cross inside a junction, and links that yield to each other in a cycle.
#include <string>
#include <vector>

namespace orch {

// netconvert 1.15 can make two connections from neighbouring lanes of one edge yield to each
// other (each connection's <request> response has the other's bit): a lane turning left
// across its left neighbour turning partly right (dir "l" against "R"). Vehicles waiting at
// the end of both lanes then wait for each other for ever (seed 200 of the generated city
// maps). Its lane-level rule (NBNode::rightTurnConflict: a turn from the left lane across the
// right lane's path yields; a left turn does not yield to a right turn from the lane to its
// left) means to let the right lane go; the exception for the left turn tests the wrong
// direction variable for "partly right" (d1 where d2 is meant), so both yield.
// Returns `net` (a SUMO net's text) with such pairs resolved as the rule means: the
// connection from the lower lane index (the right lane) no longer yields to the other; where
// it then yields to nothing, its state becomes major ("M", as netconvert writes it). Only
// the affected attributes change (same length, so the rest of the file keeps its bytes).
// One line per resolved pair is added to `notes`.
// Also, on priority junctions: links that yield to each other in a cycle (A to B, B to C, C to
// A; seed 449's J0, five approaches each waiting for the next) are put in one order, the link
// yielding to the fewest first, a yield against that order turned round (junction_right_of_way.cpp,
// break_yield_cycles); one note per cycle.
std::string without_mutual_yields(std::string net, std::vector<std::string>& notes);

}  // namespace orch
