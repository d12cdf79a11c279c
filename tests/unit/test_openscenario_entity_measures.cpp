// Freespace distances in an entity's frame (openscenario/entity_measures.hpp): between the
// boxes as they are turned, the standard's "closest bounding box points". esmini's
// highway_merge_advanced.xosc starts an event on a cartesian freespace distance between a car
// on the motorway and one on the ramp, turned 0.65 rad against it: with the other box taken as
// unturned the distance came out 1 m too long and the event started 3 steps late.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "openscenario/entity_measures.hpp"

namespace orch::openscenario {
namespace {

struct Placed {
  EntityState state;
  BoundingBox box;
  Placed(double x, double y, double heading, double length, double width) {
    state.pose = {x, y, heading};
    box.length = length;
    box.width = width;
  }
  [[nodiscard]] Body body() const { return {&state, &box}; }
};

double freespace(const Placed& from, const Placed& to, const char* type) {
  return relative_distance(from.body(), to.body(), type, "entity", true);
}

TEST(OpenScenarioEntityMeasures, FreespaceBetweenBoxesAlignedWithEachOther) {
  const Placed from(0, 0, 0, 4, 2);
  const Placed ahead(10, 5, 0, 4, 2);  // x in [8, 12], y in [4, 6]; from: x in [-2, 2], y in [-1, 1]
  EXPECT_NEAR(freespace(from, ahead, "longitudinal"), 6.0, 1e-9);
  EXPECT_NEAR(freespace(from, ahead, "lateral"), 3.0, 1e-9);
  EXPECT_NEAR(freespace(from, ahead, "cartesianDistance"), std::hypot(6.0, 3.0), 1e-9);
  EXPECT_NEAR(freespace(from, ahead, "euclidianDistance"), std::hypot(6.0, 3.0), 1e-9);
  // Without freespace: the reference points.
  EXPECT_NEAR(relative_distance(from.body(), ahead.body(), "cartesianDistance", "entity", false), std::hypot(10.0, 5.0),
              1e-9);
}

TEST(OpenScenarioEntityMeasures, FreespaceToATurnedBoxIsToItsCornersAsTheyAre) {
  const Placed from(0, 0, 0, 4, 2);
  const Placed across(10, 0, std::numbers::pi / 2, 4, 2);  // turned: x in [9, 11], y in [-2, 2]
  EXPECT_NEAR(freespace(from, across, "longitudinal"), 7.0, 1e-9);  // was 6 with the box unturned
  EXPECT_NEAR(freespace(from, across, "lateral"), 0.0, 1e-9);       // side by side across
  EXPECT_NEAR(freespace(from, across, "cartesianDistance"), 7.0, 1e-9);
  // Turned 45 degrees, its nearest corner towards from's front: the true distance between the
  // boxes is from that corner to from's front edge.
  const double h = std::numbers::pi / 4;
  const Placed diagonal(10, 0, h, 4, 2);
  const double reach = 2 * std::cos(h) + 1 * std::sin(h);  // the corner's reach back along x
  EXPECT_NEAR(freespace(from, diagonal, "cartesianDistance"), 10 - reach - 2, 1e-9);
  // Overlapping boxes are 0 apart.
  EXPECT_EQ(freespace(from, Placed(1, 1, 0.3, 4, 2), "cartesianDistance"), 0.0);
}

}  // namespace
}  // namespace orch::openscenario
