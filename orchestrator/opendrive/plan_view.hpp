#pragma once
// The OpenDRIVE reference line (planView): a sequence of geometry records, each a line,
// arc, spiral (clothoid), cubic polynomial or parametric cubic, evaluated in the
// OpenDRIVE inertial frame, in the plane (the road's elevation and superelevation: Road).
//
// A PlanView answers pose(s) and curvature(s) in O(log g) for g records: the record by
// binary search on s, and a spiral's or cubic polynomial's integral from a table of the
// record's integrals at knots every <= 2 m, built once, plus one quadrature piece (a
// parametric cubic's p is found where its arc length is s, by the same table). It also
// keeps the reference line sampled about every metre in a PointTree, so projecting a point
// onto the road finds its nearest sample without walking the road.
#include <cstddef>
#include <variant>
#include <vector>

#include "opendrive/point_tree.hpp"

namespace orch::opendrive {

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double heading = 0.0;  // rad, counter-clockwise from +x
};

struct Line {};
struct Arc {
  double curvature = 0.0;  // 1/m, positive = turning left
};
struct Spiral {  // curvature changes linearly with s from curv_start to curv_end
  double curv_start = 0.0;
  double curv_end = 0.0;
};
struct Poly3 {  // v(u) = a + b u + c u^2 + d u^3 in the local (u, v) frame
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
};
struct ParamPoly3 {  // u(p), v(p) cubics; p in [0, 1] (normalized) or [0, length] (arcLength)
  double au = 0.0, bu = 0.0, cu = 0.0, du = 0.0;
  double av = 0.0, bv = 0.0, cv = 0.0, dv = 0.0;
  bool normalized = true;
};
using Shape = std::variant<Line, Arc, Spiral, Poly3, ParamPoly3>;

struct Geometry {
  double s = 0.0;  // start along the reference line
  Pose2 start;
  double length = 0.0;
  Shape shape;
};

// Pose at `ds` metres along one geometry record (0 <= ds <= length), integrated from the
// record's start (O(ds) for spirals and cubic polynomials; PlanView caches instead).
Pose2 evaluate(const Geometry& geometry, double ds);
// Signed curvature (1/m) at `ds` along one geometry record.
double curvature(const Geometry& geometry, double ds);

// A record's integrals at knots `piece` metres apart (spiral: along s, the offsets u and v
// from its start; poly3: along u, the arc length; parametric cubic: along p scaled to
// [0, length], the arc length), so an evaluation integrates one piece.
struct GeometryTable {
  double piece = 0.0;      // 0: no table (lines, arcs: closed forms)
  std::vector<double> a;   // spiral: u at the knots; poly3, parametric cubic: arc length at the knots
  std::vector<double> b;   // spiral: v at the knots
};
GeometryTable make_table(const Geometry& geometry);
// evaluate() / curvature() with the record's table.
Pose2 evaluate(const Geometry& geometry, const GeometryTable& table, double ds);
double curvature(const Geometry& geometry, const GeometryTable& table, double ds);

class PlanView {
 public:
  PlanView() = default;
  explicit PlanView(std::vector<Geometry> geometries);
  [[nodiscard]] const std::vector<Geometry>& geometries() const { return geometries_; }
  [[nodiscard]] double length() const;
  // Pose of the reference line at `s` (clamped to [0, length]).
  [[nodiscard]] Pose2 pose(double s) const;
  [[nodiscard]] double curvature(double s) const;

  // The reference line sampled at s_i = length * i / (n - 1), n = max(2, ceil(length) + 1):
  // the coarse stage of a projection onto the road.
  [[nodiscard]] std::size_t sample_count() const { return samples_.size(); }
  [[nodiscard]] double sample_s(std::size_t i) const;
  [[nodiscard]] const PointTree& samples() const { return samples_; }

 private:
  [[nodiscard]] std::size_t record_at(double s) const;
  std::vector<Geometry> geometries_;
  std::vector<GeometryTable> tables_;  // one per record
  PointTree samples_;
};

}  // namespace orch::opendrive
