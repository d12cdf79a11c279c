#pragma once
// Hand-built views for the R157 reference driver's unit tests: a straight road with lanes
// 3.5 m wide and a 4.5 m x 1.8 m ego, and cars on it. Header only.
#include <string>

#include "reference_driver/r157_driver.hpp"

namespace orch::reference_driver::test {

inline DriverView straight_road(double time, double step, double ego_s, double ego_speed, double set_speed) {
  DriverView v;
  v.time = time;
  v.step = step;
  v.ego = {ego_s, 0.0, ego_speed, 4.5, 1.8};
  v.lane_width = 3.5;
  v.set_speed = set_speed;
  return v;
}

inline PerceivedObject car(const std::string& id, double s, double d, double speed) {
  PerceivedObject o;
  o.id = id;
  o.s = s;
  o.d = d;
  o.length = 4.5;
  o.width = 1.8;
  o.speed_s = speed;
  return o;
}

}  // namespace orch::reference_driver::test
