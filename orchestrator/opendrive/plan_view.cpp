#include "opendrive/plan_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/checked_numeric.hpp"

namespace orch::opendrive {
namespace {

// 8-point Gauss-Legendre nodes and weights on [-1, 1]: exact for polynomials up to
// degree 15, so on pieces of a few metres the integrals below are accurate to ~1e-12 m.
constexpr std::array<double, 8> kNodes = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                          -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                          0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                            0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                            0.2223810344533745, 0.1012285362903763};
constexpr double kPieceLength = 2.0;  // metres per quadrature piece

// Integral of f over [a, b] by composite Gauss-Legendre.
template <class F>
double integrate(F&& f, double a, double b, double piece) {
  if (b <= a) return 0.0;
  const int pieces = pieces_covering(b - a, piece, 1, 1 << 30);
  const double h = (b - a) / pieces;
  double sum = 0.0;
  for (int i = 0; i < pieces; ++i) {
    const double mid = a + (i + 0.5) * h;
    for (std::size_t k = 0; k < kNodes.size(); ++k) sum += kWeights[k] * f(mid + 0.5 * h * kNodes[k]);
  }
  return 0.5 * h * sum;
}

// Samples of the reference line for projections: about one per metre, both ends included.
std::size_t sample_count_for(double length) {
  return static_cast<std::size_t>(pieces_covering(length, 1.0, 1, 1 << 30)) + 1;
}

Pose2 local_to_world(const Pose2& start, double u, double v, double local_heading) {
  const double c = std::cos(start.heading);
  const double s = std::sin(start.heading);
  return {start.x + c * u - s * v, start.y + s * u + c * v, start.heading + local_heading};
}

// The table's knot at or below x (0 <= x), and the knot's position.
std::size_t knot_below(const GeometryTable& table, double x) {
  const auto last = table.a.size() - 1;
  return std::min(last, static_cast<std::size_t>(std::max(x, 0.0) / table.piece));
}

// Integral of f from 0 to x: the table's value at the knot below x plus one piece (at most
// `piece` metres, as accurate as a piece of the direct integration), or the direct
// integration without a table. `knots` holds the integral at the knots.
template <class F>
double integral_to(F&& f, const GeometryTable* table, const std::vector<double>& knots, double x) {
  if (table == nullptr || table->piece <= 0) return integrate(f, 0.0, x, kPieceLength);
  if (x <= 0) return 0.0;
  const std::size_t k = knot_below(*table, x);
  const double from = static_cast<double>(k) * table->piece;
  return knots[k] + integrate(f, from, x, table->piece + 1e-9 * (1.0 + from));
}

double poly3_speed(const Poly3& p, double u) {
  const double dv = p.b + 2 * p.c * u + 3 * p.d * u * u;
  return std::sqrt(1.0 + dv * dv);
}

// Arc length of the poly3 curve (u, v(u)) from 0 to u.
double poly3_arc_length(const Poly3& p, const GeometryTable* table, double u) {
  const auto speed = [&](double x) { return poly3_speed(p, x); };
  return table == nullptr ? integrate(speed, 0.0, u, kPieceLength) : integral_to(speed, table, table->a, u);
}

// The u at which the poly3 curve has run `ds` metres (Newton; ds' = sqrt(1 + v'^2) >= 1).
double poly3_u_at(const Poly3& p, const GeometryTable* table, double ds) {
  double u = ds;
  for (int i = 0; i < 50; ++i) {
    const double step = (poly3_arc_length(p, table, u) - ds) / poly3_speed(p, u);
    u -= step;
    if (std::abs(step) < 1e-12) break;
  }
  return u;
}

// A parametric cubic's parameter p at x metres of the record's own scale: p runs over [0, 1]
// (normalized) or [0, length] (arcLength) as x runs over [0, length].
double param_p(const Geometry& g, const ParamPoly3& p, double x) {
  return p.normalized ? (g.length > 0 ? x / g.length : 0.0) : x;
}

// |d(u, v)/dx|: how fast the curve runs as x advances.
double param_speed(const Geometry& g, const ParamPoly3& p, double x) {
  const double t = param_p(g, p, x);
  const double du = p.bu + 2 * p.cu * t + 3 * p.du * t * t;
  const double dv = p.bv + 2 * p.cv * t + 3 * p.dv * t * t;
  const double dp_dx = p.normalized ? (g.length > 0 ? 1.0 / g.length : 0.0) : 1.0;
  return std::hypot(du, dv) * dp_dx;
}

// Arc length of the parametric cubic from x = 0 to x.
double param_arc_length(const Geometry& g, const ParamPoly3& p, const GeometryTable* table, double x) {
  const auto speed = [&](double y) { return param_speed(g, p, y); };
  return table == nullptr || table->piece <= 0 ? integrate(speed, 0.0, x, kPieceLength)
                                               : integral_to(speed, table, table->a, x);
}

// The parameter p at `ds` metres along the record. OpenDRIVE's s is the length along the
// reference line in metres (its reference line coordinate system), also on a parametric
// cubic, whose p does not run at a constant speed: p is where the curve's arc
// length is ds, the curve's length scaled to the record's `length` (the two differ a little
// in real files; esmini scales the same way). Safeguarded Newton on x in [0, length].
// `total`: the curve's whole arc length (param_arc_length at the record's length).
double param_p_at(const Geometry& g, const ParamPoly3& p, const GeometryTable* table, double ds, double total) {
  if (!(total > 0) || !(g.length > 0) || ds <= 0 || ds >= g.length) return param_p(g, p, ds);
  const double target = ds * total / g.length;
  double lo = 0.0, hi = g.length, x = ds;
  for (int i = 0; i < 100; ++i) {
    const double error = param_arc_length(g, p, table, x) - target;
    if (error == 0) break;
    (error > 0 ? hi : lo) = x;
    const double speed = param_speed(g, p, x);
    double next = speed > 1e-12 ? x - error / speed : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - x) < 1e-12 * (1.0 + g.length);
    x = next;
    if (done) break;
  }
  return param_p(g, p, x);
}

double spiral_rate(const Geometry& g, const Spiral& sp) {
  return g.length > 0 ? (sp.curv_end - sp.curv_start) / g.length : 0.0;
}

struct Evaluator {
  double ds;
  const Geometry& g;
  const GeometryTable* table;  // nullptr: integrate from the record's start
  Pose2 operator()(const Line&) const { return local_to_world(g.start, ds, 0.0, 0.0); }
  Pose2 operator()(const Arc& a) const {
    if (std::abs(a.curvature) < 1e-15) return local_to_world(g.start, ds, 0.0, 0.0);
    const double angle = a.curvature * ds;
    const double r = 1.0 / a.curvature;
    return local_to_world(g.start, r * std::sin(angle), r * (1.0 - std::cos(angle)), angle);
  }
  Pose2 operator()(const Spiral& sp) const {
    // heading(s) = k0 s + (k1 - k0) s^2 / (2 L); position = integral of (cos, sin) heading.
    const double rate = spiral_rate(g, sp);
    const auto heading = [&](double s) { return sp.curv_start * s + 0.5 * rate * s * s; };
    const auto cos_h = [&](double s) { return std::cos(heading(s)); };
    const auto sin_h = [&](double s) { return std::sin(heading(s)); };
    const bool cached = table != nullptr && table->piece > 0;
    const double u = cached ? integral_to(cos_h, table, table->a, ds) : integrate(cos_h, 0.0, ds, kPieceLength);
    const double v = cached ? integral_to(sin_h, table, table->b, ds) : integrate(sin_h, 0.0, ds, kPieceLength);
    return local_to_world(g.start, u, v, heading(ds));
  }
  Pose2 operator()(const Poly3& p) const {
    const double u = poly3_u_at(p, table, ds);
    const double v = p.a + p.b * u + p.c * u * u + p.d * u * u * u;
    const double dv = p.b + 2 * p.c * u + 3 * p.d * u * u;
    return local_to_world(g.start, u, v, std::atan(dv));
  }
  Pose2 operator()(const ParamPoly3& p) const {
    const double t = param_p_at(g, p, table, ds, param_arc_length(g, p, table, g.length));
    const double u = p.au + p.bu * t + p.cu * t * t + p.du * t * t * t;
    const double v = p.av + p.bv * t + p.cv * t * t + p.dv * t * t * t;
    const double du = p.bu + 2 * p.cu * t + 3 * p.du * t * t;
    const double dv = p.bv + 2 * p.cv * t + 3 * p.dv * t * t;
    return local_to_world(g.start, u, v, std::atan2(dv, du));
  }
};

struct CurvatureOf {
  double ds;
  const Geometry& g;
  const GeometryTable* table;
  double operator()(const Line&) const { return 0.0; }
  double operator()(const Arc& a) const { return a.curvature; }
  double operator()(const Spiral& sp) const {
    return g.length > 0 ? sp.curv_start + (sp.curv_end - sp.curv_start) * ds / g.length : sp.curv_start;
  }
  double operator()(const Poly3& p) const {
    const double u = poly3_u_at(p, table, ds);
    const double dv = p.b + 2 * p.c * u + 3 * p.d * u * u;
    const double ddv = 2 * p.c + 6 * p.d * u;
    return ddv / std::pow(1.0 + dv * dv, 1.5);
  }
  double operator()(const ParamPoly3& p) const {
    // Per metre of s: the curve's curvature times its length over the record's (1 in a
    // file whose length is the curve's).
    const double total = param_arc_length(g, p, table, g.length);
    const double scale = total > 0 && g.length > 0 ? total / g.length : 1.0;
    const double t = param_p_at(g, p, table, ds, total);
    const double du = p.bu + 2 * p.cu * t + 3 * p.du * t * t;
    const double dv = p.bv + 2 * p.cv * t + 3 * p.dv * t * t;
    const double ddu = 2 * p.cu + 6 * p.du * t;
    const double ddv = 2 * p.cv + 6 * p.dv * t;
    const double speed = std::hypot(du, dv);
    return speed > 0 ? scale * (du * ddv - dv * ddu) / (speed * speed * speed) : 0.0;
  }
};

}  // namespace

Pose2 evaluate(const Geometry& geometry, double ds) {
  return std::visit(Evaluator{std::clamp(ds, 0.0, geometry.length), geometry, nullptr}, geometry.shape);
}

double curvature(const Geometry& geometry, double ds) {
  return std::visit(CurvatureOf{std::clamp(ds, 0.0, geometry.length), geometry, nullptr}, geometry.shape);
}

Pose2 evaluate(const Geometry& geometry, const GeometryTable& table, double ds) {
  return std::visit(Evaluator{std::clamp(ds, 0.0, geometry.length), geometry, &table}, geometry.shape);
}

double curvature(const Geometry& geometry, const GeometryTable& table, double ds) {
  return std::visit(CurvatureOf{std::clamp(ds, 0.0, geometry.length), geometry, &table}, geometry.shape);
}

GeometryTable make_table(const Geometry& g) {
  GeometryTable table;
  if (!(g.length > 0) || !std::isfinite(g.length)) return table;
  // Knots every <= 2 m, each piece integrated as one piece of the direct integration is.
  const auto pieces = static_cast<std::size_t>(pieces_covering(g.length, kPieceLength, 1, 1 << 30));
  const double piece = g.length / static_cast<double>(pieces);
  const auto fill = [&](std::vector<double>& knots, auto&& f) {
    knots.assign(pieces + 1, 0.0);
    for (std::size_t k = 0; k < pieces; ++k) {
      const double from = static_cast<double>(k) * piece;
      knots[k + 1] = knots[k] + integrate(f, from, static_cast<double>(k + 1) * piece, piece + 1e-9 * (1.0 + from));
    }
  };
  if (const auto* sp = std::get_if<Spiral>(&g.shape)) {
    const double rate = spiral_rate(g, *sp);
    const auto heading = [&](double s) { return sp->curv_start * s + 0.5 * rate * s * s; };
    table.piece = piece;
    fill(table.a, [&](double s) { return std::cos(heading(s)); });
    fill(table.b, [&](double s) { return std::sin(heading(s)); });
  } else if (const auto* p = std::get_if<Poly3>(&g.shape)) {
    // u runs at most as far as s (ds/du >= 1), so knots over u in [0, length] cover the record.
    table.piece = piece;
    fill(table.a, [&](double u) { return poly3_speed(*p, u); });
  } else if (const auto* pp = std::get_if<ParamPoly3>(&g.shape)) {
    // Over x in [0, length] (p scaled to it): the curve's arc length at the knots.
    table.piece = piece;
    fill(table.a, [&](double x) { return param_speed(g, *pp, x); });
  }
  return table;
}

PlanView::PlanView(std::vector<Geometry> geometries) : geometries_(std::move(geometries)) {
  std::stable_sort(geometries_.begin(), geometries_.end(),
                   [](const Geometry& a, const Geometry& b) { return a.s < b.s; });
  tables_.reserve(geometries_.size());
  for (const Geometry& g : geometries_) tables_.push_back(make_table(g));
  const std::size_t n = sample_count_for(length());
  std::vector<double> xs(n), ys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Pose2 p = pose(length() * static_cast<double>(i) / static_cast<double>(n - 1));
    xs[i] = p.x;
    ys[i] = p.y;
  }
  samples_ = PointTree(std::move(xs), std::move(ys));
}

double PlanView::length() const {
  if (geometries_.empty()) return 0.0;
  return geometries_.back().s + geometries_.back().length;
}

double PlanView::sample_s(std::size_t i) const {
  return length() * static_cast<double>(i) / static_cast<double>(samples_.size() - 1);
}

std::size_t PlanView::record_at(double s) const {
  // The last record starting at or before s.
  auto it = std::upper_bound(geometries_.begin(), geometries_.end(), s,
                             [](double value, const Geometry& g) { return value < g.s; });
  if (it != geometries_.begin()) --it;
  return static_cast<std::size_t>(it - geometries_.begin());
}

Pose2 PlanView::pose(double s) const {
  if (geometries_.empty()) return {};
  const std::size_t i = record_at(s);
  return evaluate(geometries_[i], tables_[i], s - geometries_[i].s);
}

double PlanView::curvature(double s) const {
  if (geometries_.empty()) return 0.0;
  const std::size_t i = record_at(s);
  return opendrive::curvature(geometries_[i], tables_[i], s - geometries_[i].s);
}

}  // namespace orch::opendrive
