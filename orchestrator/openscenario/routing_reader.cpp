// RoutingAction: routes (AssignRouteAction, inline or from a RouteCatalog) and
// trajectories (FollowTrajectoryAction: Polyline, Clothoid and Nurbs shapes, inline or from a
// TrajectoryCatalog, with TimeReference and TrajectoryFollowingMode).
#include <algorithm>

#include <fmt/format.h>

#include "openscenario/reader_context.hpp"
#include "openscenario/route_plan.hpp"

namespace orch::openscenario::reading {
namespace {

AssignRouteAction read_route(Element& route) {
  AssignRouteAction a;
  a.name = route.text("name");
  a.closed = route.optional_boolean("closed").value_or(false);
  route.ignore_children({"ParameterDeclarations"});  // read by Context::resolve or open_scope
  for (Element waypoint : route.children("Waypoint")) {
    a.strategies.push_back(waypoint.choice<std::string>("routeStrategy", {{"fastest", "fastest"},
                                                                          {"shortest", "shortest"},
                                                                          {"leastIntersections", "leastIntersections"},
                                                                          {"random", "random"}}));
    a.waypoint_places.push_back(waypoint.place());
    Element position = waypoint.child("Position");
    a.waypoints.push_back(read_position(position));
    waypoint.finish();
  }
  if (a.waypoints.size() < 2) route.fail("a Route needs at least two Waypoints");
  route.finish();
  return a;
}

PolylineShape read_polyline(Element& polyline) {
  PolylineShape shape;
  for (Element vertex : polyline.children("Vertex")) {
    TrajectoryVertex v;
    v.time = vertex.optional_number("time");
    Element position = vertex.child("Position");
    v.position = read_position(position);
    vertex.finish();
    shape.vertices.push_back(std::move(v));
  }
  if (shape.vertices.size() < 2) polyline.fail("a Polyline needs at least two Vertex elements");
  const bool timed = shape.vertices.front().time.has_value();
  for (std::size_t i = 0; i < shape.vertices.size(); ++i) {
    if (shape.vertices[i].time.has_value() != timed)
      polyline.fail("give a time to every Vertex of the Polyline or to none");
    if (timed && i > 0 && *shape.vertices[i].time < *shape.vertices[i - 1].time)
      polyline.fail(fmt::format("Vertex {} has an earlier time than the one before", i + 1));
  }
  polyline.finish();
  return shape;
}

ClothoidShape read_clothoid(Element& clothoid) {
  ClothoidShape shape;
  shape.curvature = clothoid.number("curvature");
  // curvatureDot (1.0, 1.1) was renamed curvaturePrime in 1.2.
  const auto dot = clothoid.optional_number("curvatureDot");
  const auto prime = clothoid.optional_number("curvaturePrime");
  if (dot && prime) clothoid.fail("give curvaturePrime or curvatureDot, not both");
  shape.curvature_dot = prime ? *prime : dot.value_or(0.0);
  shape.length = clothoid.number("length");
  if (shape.length <= 0) clothoid.fail_attribute("length", "a Clothoid's length must be positive");
  shape.start_time = clothoid.optional_number("startTime");
  shape.stop_time = clothoid.optional_number("stopTime");
  if (shape.start_time.has_value() != shape.stop_time.has_value())
    clothoid.fail("give both startTime and stopTime, or neither");
  if (shape.start_time && *shape.stop_time <= *shape.start_time)
    clothoid.fail_attribute("stopTime", "stopTime must be after startTime");
  Element position = clothoid.child("Position");
  shape.start = read_position(position);
  clothoid.finish();
  return shape;
}

ClothoidSplineShape read_clothoid_spline(Element& spline) {
  ClothoidSplineShape shape;
  shape.time_end = spline.optional_number("timeEnd");
  for (Element e : spline.children("ClothoidSplineSegment")) {
    ClothoidSplineSegment segment;
    segment.curvature_start = e.number("curvatureStart");
    segment.curvature_end = e.number("curvatureEnd");
    segment.length = e.number("length");
    if (!(segment.length > 0)) e.fail_attribute("length", "a ClothoidSplineSegment's length must be positive");
    segment.heading_offset = e.optional_number("hOffset").value_or(0.0);
    segment.time_start = e.optional_number("timeStart");
    if (auto start = e.optional_child("PositionStart")) segment.start = read_position(*start);
    e.finish();
    if (segment.time_start.has_value() != shape.time_end.has_value())
      e.fail(shape.time_end ? "the ClothoidSpline has a timeEnd: give every ClothoidSplineSegment a timeStart"
                            : "a ClothoidSplineSegment's timeStart needs the ClothoidSpline's timeEnd");
    if (segment.time_start && !shape.segments.empty() && *segment.time_start < *shape.segments.back().time_start)
      e.fail_attribute("timeStart", "timeStart is earlier than the one of the segment before");
    shape.segments.push_back(std::move(segment));
  }
  if (shape.segments.empty()) spline.fail("a ClothoidSpline needs at least one ClothoidSplineSegment");
  if (shape.time_end && *shape.time_end <= *shape.segments.back().time_start)
    spline.fail_attribute("timeEnd", "timeEnd must be after the last segment's timeStart");
  spline.finish();
  return shape;
}

NurbsShape read_nurbs(Element& nurbs) {
  NurbsShape shape;
  shape.order = nurbs.integer("order");
  if (shape.order < 1) nurbs.fail_attribute("order", "a Nurbs' order must be at least 1");
  for (Element control : nurbs.children("ControlPoint")) {
    NurbsControlPoint c;
    c.time = control.optional_number("time");
    c.weight = control.optional_number("weight").value_or(1.0);
    if (!(c.weight > 0)) control.fail_attribute("weight", "a control point's weight must be positive");
    Element position = control.child("Position");
    c.position = read_position(position);
    control.finish();
    shape.points.push_back(std::move(c));
  }
  for (Element knot : nurbs.children("Knot")) {
    shape.knots.push_back(knot.number("value"));
    if (shape.knots.size() > 1 && shape.knots.back() < shape.knots[shape.knots.size() - 2])
      knot.fail_attribute("value", "knots must not decrease");
    knot.finish();
  }
  const auto order = static_cast<std::size_t>(shape.order);
  if (shape.points.size() < std::max<std::size_t>(order, 2))
    nurbs.fail(fmt::format("a Nurbs of order {} needs at least {} ControlPoint elements, it has {}", shape.order,
                           std::max<std::size_t>(order, 2), shape.points.size()));
  if (shape.knots.size() != shape.points.size() + order)
    nurbs.fail(fmt::format("a Nurbs of order {} with {} control points needs {} Knot elements (points + order), "
                           "it has {}",
                           shape.order, shape.points.size(), shape.points.size() + order, shape.knots.size()));
  const bool timed = shape.points.front().time.has_value();
  for (const NurbsControlPoint& c : shape.points)
    if (c.time.has_value() != timed) nurbs.fail("give a time to every ControlPoint of the Nurbs or to none");
  nurbs.finish();
  return shape;
}

Trajectory read_trajectory(Element& e) {
  Trajectory t;
  t.name = e.text("name");
  t.closed = e.boolean("closed");  // the path returns to its start (close_path, trajectory_motion.hpp)
  e.ignore_children({"ParameterDeclarations"});  // read by Context::resolve or open_scope
  Element holder = e.child("Shape");
  Element shape = holder.one_of({"Polyline", "Clothoid", "ClothoidSpline", "Nurbs"});
  holder.finish();
  if (shape.name() == "Polyline") t.shape = read_polyline(shape);
  else if (shape.name() == "Nurbs") t.shape = read_nurbs(shape);
  else if (shape.name() == "ClothoidSpline") t.shape = read_clothoid_spline(shape);
  else t.shape = read_clothoid(shape);
  e.finish();
  return t;
}

// A Trajectory inline or a CatalogReference to one.
Trajectory read_trajectory_or_reference(Element& e, Context& context) {
  if (e.name() == "CatalogReference") {
    Element entry = context.resolve(e, {"Trajectory"});
    e.finish();
    return read_trajectory(entry);
  }
  Element scoped = open_scope(e, context, "");  // an inline Trajectory's own ParameterDeclarations
  return read_trajectory(scoped);
}

}  // namespace

namespace {

// The Route inside `holder`: written inline (with its own ParameterDeclarations) or a
// CatalogReference into a RouteCatalog.
AssignRouteAction read_route_of(Element& holder, Context& context) {
  Element source = holder.one_of({"Route", "CatalogReference"});
  if (source.name() == "CatalogReference") {
    Element entry = context.resolve(source, {"Route"});
    source.finish();
    return read_route(entry);
  }
  Element scoped = open_scope(source, context, "");  // an inline Route's own ParameterDeclarations
  return read_route(scoped);
}

}  // namespace

AssignRouteAction read_assign_route(Element& e, Context& context) {
  AssignRouteAction a = read_route_of(e, context);
  e.finish();
  return a;
}

std::shared_ptr<const position::RouteWaypoints> read_route_ref(Element& route_ref, Context& context) {
  AssignRouteAction a = read_route_of(route_ref, context);
  route_ref.finish();
  auto route = std::make_shared<position::RouteWaypoints>();
  route->name = a.name;
  for (std::size_t i = 0; i < a.waypoints.size(); ++i)
    route->waypoints.push_back({a.waypoints[i], route_strategy(a.strategies[i])});
  return route;
}

Trajectory read_trajectory_ref(Element& trajectory_ref, Context& context) {
  Element inner = trajectory_ref.one_of({"Trajectory", "CatalogReference"});
  trajectory_ref.finish();
  return read_trajectory_or_reference(inner, context);
}

FollowTrajectoryAction read_follow_trajectory(Element& e, Context& context) {
  FollowTrajectoryAction a;
  a.initial_distance_offset = e.optional_number("initialDistanceOffset").value_or(0.0);
  if (a.initial_distance_offset < 0) e.fail_attribute("initialDistanceOffset", "cannot be negative");
  // 1.2: TrajectoryRef holds the Trajectory or its CatalogReference; 1.0 and 1.1 hold them directly.
  Element source = e.one_of({"TrajectoryRef", "Trajectory", "CatalogReference"});
  if (source.name() == "TrajectoryRef") {
    Element inner = source.one_of({"Trajectory", "CatalogReference"});
    a.trajectory = read_trajectory_or_reference(inner, context);
    source.finish();
  } else {
    a.trajectory = read_trajectory_or_reference(source, context);
  }
  Element reference = e.child("TimeReference");
  Element timing = reference.one_of({"None", "Timing"});
  reference.finish();
  if (timing.name() == "Timing") {
    TrajectoryTiming t;
    t.absolute = timing.choice<bool>("domainAbsoluteRelative", {{"absolute", true}, {"relative", false}});
    t.scale = timing.number("scale");
    t.offset = timing.number("offset");
    if (t.scale <= 0) timing.fail_attribute("scale", "a timing scale must be positive");
    a.timing = t;
  }
  timing.finish();
  Element mode = e.child("TrajectoryFollowingMode");
  a.follow_mode = mode.choice<bool>("followingMode", {{"position", false}, {"follow", true}});
  mode.finish();
  if (a.timing) {
    const bool timed = std::visit(
        [](const auto& shape) {
          if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, PolylineShape>)
            return shape.vertices.front().time.has_value();
          else if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, NurbsShape>)
            return shape.points.front().time.has_value();
          else if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, ClothoidSplineShape>)
            return shape.time_end.has_value();
          else
            return shape.start_time.has_value();
        },
        a.trajectory.shape);
    if (!timed)
      e.fail("a Timing needs vertex times (Polyline), control point times (Nurbs), startTime and stopTime (Clothoid) "
             "or timeStart and timeEnd (ClothoidSpline)");
  }
  e.finish();
  return a;
}

}  // namespace orch::openscenario::reading
