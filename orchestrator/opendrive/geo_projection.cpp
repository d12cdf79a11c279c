#include "opendrive/geo_projection.hpp"

#include <dlfcn.h>

#include <cmath>
#include <mutex>
#include <string>

#include <fmt/format.h>
#include <proj.h>

#include "core/errors.hpp"

namespace orch::opendrive {
namespace {

// PROJ is opened when a scenario first needs it (a GeoPosition), not linked into the program:
// linked, PROJ and the ~36 libraries it needs (SQLite, libtiff, curl, GnuTLS, Kerberos, ...)
// sit in the program's global symbol scope, which the dynamic loader searches first for every
// symbol of every library loaded later; libsumocpp.so binds ~56,000 symbols at load (most of
// them its own), so they cost 10-16 % of a short run's instructions (docs/performance.md,
// "The corpus against esmini"). libsumocpp.so needs PROJ too and loads
// it in its own scope; opening it here afterwards (or before) gives the same library, matched
// by its soname, which the build takes from PROJ's CMake package (ORCH_PROJ_SONAME).
struct ProjApi {
  decltype(&proj_context_create) context_create;
  decltype(&proj_context_destroy) context_destroy;
  decltype(&proj_context_errno) context_errno;
  decltype(&proj_context_errno_string) context_errno_string;
  decltype(&proj_log_level) log_level;
  decltype(&proj_create) create;
  decltype(&proj_create_crs_to_crs) create_crs_to_crs;
  decltype(&proj_normalize_for_visualization) normalize_for_visualization;
  decltype(&proj_is_crs) is_crs;
  decltype(&proj_destroy) destroy;
  decltype(&proj_trans) trans;
  decltype(&proj_coord) coord;
  decltype(&proj_torad) torad;
  decltype(&proj_todeg) todeg;
};

template <typename F>
void bind_symbol(void* library, F& function, const char* name, std::string& missing) {
  function = reinterpret_cast<F>(dlsym(library, name));
  if (!function) missing += missing.empty() ? name : std::string(", ") + name;
}

const ProjApi& proj_api() {
  static ProjApi api{};
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    void* library = dlopen(ORCH_PROJ_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!library) {
      const char* why = dlerror();
      failure = fmt::format("PROJ ({}) could not be loaded: {} (install Debian's libproj25)", ORCH_PROJ_SONAME,
                            why ? why : "unknown reason");
      return;
    }
    std::string missing;
    bind_symbol(library, api.context_create, "proj_context_create", missing);
    bind_symbol(library, api.context_destroy, "proj_context_destroy", missing);
    bind_symbol(library, api.context_errno, "proj_context_errno", missing);
    bind_symbol(library, api.context_errno_string, "proj_context_errno_string", missing);
    bind_symbol(library, api.log_level, "proj_log_level", missing);
    bind_symbol(library, api.create, "proj_create", missing);
    bind_symbol(library, api.create_crs_to_crs, "proj_create_crs_to_crs", missing);
    bind_symbol(library, api.normalize_for_visualization, "proj_normalize_for_visualization", missing);
    bind_symbol(library, api.is_crs, "proj_is_crs", missing);
    bind_symbol(library, api.destroy, "proj_destroy", missing);
    bind_symbol(library, api.trans, "proj_trans", missing);
    bind_symbol(library, api.coord, "proj_coord", missing);
    bind_symbol(library, api.torad, "proj_torad", missing);
    bind_symbol(library, api.todeg, "proj_todeg", missing);
    if (!missing.empty())
      failure = fmt::format("PROJ ({}) lacks {}: not the PROJ this program was built with", ORCH_PROJ_SONAME, missing);
  });
  if (!failure.empty()) throw MapError("longitude and latitude need PROJ: " + failure);
  return api;
}

}  // namespace

struct GeoProjection::Proj {
  const ProjApi& api = proj_api();
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
    if (transform) api.destroy(transform);
    if (context) api.context_destroy(context);
  }
  [[nodiscard]] std::string error() const {
    return api.context_errno_string(context, api.context_errno(context));
  }
};

GeoProjection::GeoProjection(const GeoReference& reference)
    : reference_(reference) {
  if (reference.proj.empty())
    throw MapError("the road network has no geoReference (the OpenDRIVE header's <geoReference>, a PROJ string): "
                   "longitude and latitude cannot be placed on it");
  proj_ = std::make_unique<Proj>();  // loads PROJ on first use
  proj_->context = proj_->api.context_create();
  proj_->api.log_level(proj_->context, PJ_LOG_NONE);
  PJ* given = proj_->api.create(proj_->context, reference.proj.c_str());
  if (!given)
    throw MapError(fmt::format("geoReference \"{}\": PROJ cannot read it ({})", reference.proj, proj_->error()));
  if (proj_->api.is_crs(given)) {
    proj_->bare = false;
    PJ* raw = proj_->api.create_crs_to_crs(proj_->context, "EPSG:4326", reference.proj.c_str(), nullptr);
    proj_->api.destroy(given);
    if (!raw)
      throw MapError(fmt::format("geoReference \"{}\": PROJ finds no way from WGS 84 to it ({})", reference.proj,
                                 proj_->error()));
    proj_->transform = proj_->api.normalize_for_visualization(proj_->context, raw);  // longitude, latitude
    proj_->api.destroy(raw);
    if (!proj_->transform)
      throw MapError(fmt::format("geoReference \"{}\": {}", reference.proj, proj_->error()));
  } else {
    proj_->transform = given;
  }
}

GeoProjection::~GeoProjection() = default;

Vec2 GeoProjection::local(const GeoPoint& point) const {
  const double lon = proj_->bare ? proj_->api.torad(point.longitude_deg) : point.longitude_deg;
  const double lat = proj_->bare ? proj_->api.torad(point.latitude_deg) : point.latitude_deg;
  const PJ_COORD world = proj_->api.trans(proj_->transform, PJ_FWD, proj_->api.coord(lon, lat, 0, 0));
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
  const PJ_COORD geo = proj_->api.trans(proj_->transform, PJ_INV, proj_->api.coord(x, y, 0, 0));
  if (!std::isfinite(geo.lp.lam) || !std::isfinite(geo.lp.phi))
    throw MapError(fmt::format("x {} and y {} are outside the road network's projection \"{}\"", local.x(), local.y(),
                               reference_.proj));
  if (proj_->bare) return {proj_->api.todeg(geo.lp.phi), proj_->api.todeg(geo.lp.lam)};
  return {geo.xy.y, geo.xy.x};
}

}  // namespace orch::opendrive
