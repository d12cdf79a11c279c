#include "opendrive/geo_projection.hpp"

#include <cmath>

#include <fmt/format.h>
#include <proj.h>

#include "core/errors.hpp"

namespace orch::opendrive {

struct GeoProjection::Proj {
  PJ_CONTEXT* context = nullptr;
  PJ* transform = nullptr;  // geographic -> the projected (world) frame
  // A PROJ string without "+type=crs" (what OpenDRIVE files write, e.g. "+proj=tmerc
  // +lat_0=... +datum=WGS84") is a bare projection: longitude and latitude in radians on its
  // own ellipsoid, as PROJ.4 strings always worked (and SUMO's netconvert uses them). A CRS
  // ("EPSG:25832", "+type=crs") is reached from WGS 84 in degrees, longitude first.
  bool bare = true;
  Proj() = default;
  Proj(const Proj&) = delete;
  Proj& operator=(const Proj&) = delete;
  ~Proj() {
    if (transform) proj_destroy(transform);
    if (context) proj_context_destroy(context);
  }
  [[nodiscard]] std::string error() const { return proj_context_errno_string(context, proj_context_errno(context)); }
};

GeoProjection::GeoProjection(const GeoReference& reference)
    : proj_(std::make_unique<Proj>()), reference_(reference) {
  if (reference.proj.empty())
    throw MapError("the road network has no geoReference (the OpenDRIVE header's <geoReference>, a PROJ string): "
                   "longitude and latitude cannot be placed on it");
  proj_->context = proj_context_create();
  proj_log_level(proj_->context, PJ_LOG_NONE);
  PJ* given = proj_create(proj_->context, reference.proj.c_str());
  if (!given)
    throw MapError(fmt::format("geoReference \"{}\": PROJ cannot read it ({})", reference.proj, proj_->error()));
  if (proj_is_crs(given)) {
    proj_->bare = false;
    PJ* raw = proj_create_crs_to_crs(proj_->context, "EPSG:4326", reference.proj.c_str(), nullptr);
    proj_destroy(given);
    if (!raw)
      throw MapError(fmt::format("geoReference \"{}\": PROJ finds no way from WGS 84 to it ({})", reference.proj,
                                 proj_->error()));
    proj_->transform = proj_normalize_for_visualization(proj_->context, raw);  // longitude, latitude
    proj_destroy(raw);
    if (!proj_->transform)
      throw MapError(fmt::format("geoReference \"{}\": {}", reference.proj, proj_->error()));
  } else {
    proj_->transform = given;
  }
}

GeoProjection::~GeoProjection() = default;

Vec2 GeoProjection::local(const GeoPoint& point) const {
  const double lon = proj_->bare ? proj_torad(point.longitude_deg) : point.longitude_deg;
  const double lat = proj_->bare ? proj_torad(point.latitude_deg) : point.latitude_deg;
  const PJ_COORD world = proj_trans(proj_->transform, PJ_FWD, proj_coord(lon, lat, 0, 0));
  if (!std::isfinite(world.xy.x) || !std::isfinite(world.xy.y))
    throw MapError(fmt::format("latitude {} and longitude {} degrees are outside the road network's projection \"{}\"",
                               point.latitude_deg, point.longitude_deg, reference_.proj));
  // The header offset: world = R(hdg) * local + (x, y), so local = R(-hdg) * (world - (x, y)).
  const double dx = world.xy.x - reference_.x;
  const double dy = world.xy.y - reference_.y;
  const double c = std::cos(reference_.hdg);
  const double s = std::sin(reference_.hdg);
  return {c * dx + s * dy, -s * dx + c * dy};
}

GeoPoint GeoProjection::geographic(const Vec2& local) const {
  const double c = std::cos(reference_.hdg);
  const double s = std::sin(reference_.hdg);
  const double x = c * local.x() - s * local.y() + reference_.x;
  const double y = s * local.x() + c * local.y() + reference_.y;
  const PJ_COORD geo = proj_trans(proj_->transform, PJ_INV, proj_coord(x, y, 0, 0));
  if (!std::isfinite(geo.lp.lam) || !std::isfinite(geo.lp.phi))
    throw MapError(fmt::format("x {} and y {} are outside the road network's projection \"{}\"", local.x(), local.y(),
                               reference_.proj));
  if (proj_->bare) return {proj_todeg(geo.lp.phi), proj_todeg(geo.lp.lam)};
  return {geo.xy.y, geo.xy.x};
}

}  // namespace orch::opendrive
