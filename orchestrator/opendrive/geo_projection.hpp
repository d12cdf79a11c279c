#pragma once
// Longitude and latitude (WGS 84, degrees) to a road network's own frame and back, through
// the network's geoReference (a PROJ string) and header offset (OpenDRIVE 1.6+, 8.5:
// world = R(hdg) * local + (x, y); the world frame is the PROJ string's projected one).
// OpenSCENARIO's GeoPosition is resolved with it.
#include <memory>
#include <string>

#include "core/polyline.hpp"
#include "opendrive/road_network.hpp"

namespace orch::opendrive {

struct GeoPoint {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
};

class GeoProjection {
 public:
  // Throws MapError naming the string and PROJ's reason when PROJ cannot use it (or it is empty).
  explicit GeoProjection(const GeoReference& reference);
  ~GeoProjection();
  GeoProjection(const GeoProjection&) = delete;
  GeoProjection& operator=(const GeoProjection&) = delete;

  // The network-frame point of a geographic one; MapError when PROJ cannot project it (a
  // point outside the projection's domain).
  [[nodiscard]] Vec2 local(const GeoPoint& point) const;
  [[nodiscard]] GeoPoint geographic(const Vec2& local) const;

 private:
  struct Proj;
  std::unique_ptr<Proj> proj_;
  GeoReference reference_;
};

}  // namespace orch::opendrive
