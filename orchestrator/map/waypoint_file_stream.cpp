// One streaming pass over a well-formed waypoint file (nlohmann's SAX parser): no value tree
// of 57,000 points is built, walked and freed, which was most of a run's start on the
// shipped maps (docs/performance.md). Anything a well-formed file does not have (an unknown
// or repeated key, a value of another type, too few points, no routes, invalid JSON) stops
// the pass; load_waypoint_file then reads the file with the value tree, which names the
// problem with its line and pointer.
#include <cmath>
#include <exception>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "json/json_document.hpp"
#include "map/waypoint_file_stream.hpp"

namespace orch {

namespace {

// Where the parser is: the shape of a waypoint file, one level per nesting.
enum class Level { Outside, Top, Routes, Route, Points, Point, Properties, Property };

// The fields a level may hold; each may appear once.
enum Field : unsigned {
  kNone = 0, kId = 1, kMapId = 2, kWaypoints = 4, kProperties = 8, kPoints = 16, kX = 32, kY = 64, kZ = 128,
  kV = 256, kName = 512, kIndex = 1024, kWaypointId = 2048
};

Field field_of(Level level, const std::string& key) {
  switch (level) {
    case Level::Top:
      if (key == "id") return kId;
      if (key == "mapId") return kMapId;
      if (key == "waypoints") return kWaypoints;
      if (key == "properties") return kProperties;
      return kNone;
    case Level::Route:
      if (key == "id") return kId;
      if (key == "points") return kPoints;
      return kNone;
    case Level::Point:
      if (key.size() != 1) return kNone;
      switch (key[0]) {
        case 'x': return kX;
        case 'y': return kY;
        case 'z': return kZ;
        case 'v': return kV;
        default: return kNone;
      }
    case Level::Property:
      if (key == "id") return kId;
      if (key == "name") return kName;
      if (key == "index") return kIndex;
      if (key == "waypointId") return kWaypointId;
      return kNone;
    default: return kNone;
  }
}

class WaypointStream : public nlohmann::json_sax<nlohmann::json> {
 public:
  WaypointFile file;

  bool null() override { return false; }
  bool boolean(bool) override { return false; }
  bool binary(binary_t&) override { return false; }
  bool number_integer(number_integer_t v) override { return number(static_cast<double>(v)); }
  bool number_unsigned(number_unsigned_t v) override { return number(static_cast<double>(v)); }
  bool number_float(number_float_t v, const string_t&) override { return std::isfinite(v) && number(v); }

  bool string(string_t& value) override {
    switch (field_) {
      case kId:
        (level_ == Level::Top ? file.id : level_ == Level::Route ? route_.id : property_.id) = std::move(value);
        return true;
      case kMapId: file.map_id = std::move(value); return true;
      case kName: property_.name = std::move(value); return true;
      case kWaypointId: property_.waypoint_id = std::move(value); return true;
      default: return false;
    }
  }

  bool key(string_t& key) override {
    field_ = field_of(level_, key);
    if (field_ == kNone || (seen_ & field_)) return false;
    seen_ |= field_;
    return true;
  }

  bool start_object(std::size_t) override {
    switch (level_) {
      case Level::Outside: return enter(Level::Top);
      case Level::Routes: route_ = {}; xy_.clear(); return enter(Level::Route);
      case Level::Points: x_ = y_ = z_ = v_ = std::nullopt; return enter(Level::Point);
      case Level::Properties: property_ = {}; return enter(Level::Property);
      default: return false;
    }
  }

  bool end_object() override {
    switch (level_) {
      case Level::Top:
        if (!(seen_ & kWaypoints) || file.routes.empty()) return false;
        level_ = Level::Outside;
        return true;
      case Level::Route: {
        if (!(seen_ & kId) || !(seen_ & kPoints) || file.find(route_.id)) return false;
        if (complete_route(route_, std::move(xy_))) return false;
        file.routes.push_back(std::move(route_));
        return leave(Level::Routes);
      }
      case Level::Point:
        if (!x_ || !z_) return false;
        route_.points.push_back(map_point(*x_, y_, *z_, v_));
        xy_.emplace_back(route_.points.back().x, route_.points.back().y);
        return leave(Level::Points);
      case Level::Property:
        file.properties.push_back(std::move(property_));
        return leave(Level::Properties);
      default: return false;
    }
  }

  bool start_array(std::size_t) override {
    if (level_ == Level::Top && field_ == kWaypoints) return nest(Level::Routes);
    if (level_ == Level::Top && field_ == kProperties) return nest(Level::Properties);
    if (level_ == Level::Route && field_ == kPoints) return nest(Level::Points);
    return false;
  }

  bool end_array() override {
    switch (level_) {
      case Level::Routes:
      case Level::Properties: level_ = Level::Top; seen_ = top_seen_; return true;
      case Level::Points: level_ = Level::Route; seen_ = route_seen_; return true;
      default: return false;
    }
  }

  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  bool number(double v) {
    switch (field_) {
      case kX: x_ = v; return true;
      case kY: y_ = v; return true;
      case kZ: z_ = v; return true;
      case kV: v_ = v; return true;
      case kIndex: property_.index = v; return true;
      default: return false;
    }
  }
  bool enter(Level level) {
    level_ = level;
    seen_ = 0;
    field_ = kNone;
    return true;
  }
  // Into an array of the current object: what the object has seen so far is kept for its
  // remaining keys.
  bool nest(Level level) {
    (level_ == Level::Top ? top_seen_ : route_seen_) = seen_;
    level_ = level;
    return true;
  }
  bool leave(Level level) {
    level_ = level;
    return true;
  }

  Level level_ = Level::Outside;
  Field field_ = kNone;
  unsigned seen_ = 0, top_seen_ = 0, route_seen_ = 0;
  WaypointRoute route_;
  std::vector<Vec2> xy_;
  std::optional<double> x_, y_, z_, v_;
  WaypointProperty property_;
};

}  // namespace

std::optional<WaypointFile> read_well_formed_waypoint_file(const std::string& path) {
  std::string text;
  try {
    text = read_file(path);
  } catch (const std::exception&) {
    return std::nullopt;  // the reader with messages says why
  }
  if (text.size() > kMaxJsonBytes) return std::nullopt;
  WaypointStream stream;
  if (!nlohmann::json::sax_parse(text, &stream)) return std::nullopt;
  stream.file.path = path;
  return std::move(stream.file);
}

}  // namespace orch
