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

Pose2 local_to_world(const Pose2& start, double u, double v, double local_heading) {
  const double c = std::cos(start.heading);
  const double s = std::sin(start.heading);
  return {start.x + c * u - s * v, start.y + s * u + c * v, start.heading + local_heading};
}

// Arc length of the poly3 curve (u, v(u)) from 0 to u.
double poly3_arc_length(const Poly3& p, double u) {
  return integrate(
      [&](double x) {
        const double dv = p.b + 2 * p.c * x + 3 * p.d * x * x;
        return std::sqrt(1.0 + dv * dv);
      },
      0.0, u, kPieceLength);
}

// The u at which the poly3 curve has run `ds` metres (Newton; ds' = sqrt(1 + v'^2) >= 1).
double poly3_u_at(const Poly3& p, double ds) {
  double u = ds;
  for (int i = 0; i < 50; ++i) {
    const double dv = p.b + 2 * p.c * u + 3 * p.d * u * u;
    const double step = (poly3_arc_length(p, u) - ds) / std::sqrt(1.0 + dv * dv);
    u -= step;
    if (std::abs(step) < 1e-12) break;
  }
  return u;
}

struct Evaluator {
  double ds;
  const Geometry& g;
  Pose2 operator()(const Line&) const { return local_to_world(g.start, ds, 0.0, 0.0); }
  Pose2 operator()(const Arc& a) const {
    if (std::abs(a.curvature) < 1e-15) return local_to_world(g.start, ds, 0.0, 0.0);
    const double angle = a.curvature * ds;
    const double r = 1.0 / a.curvature;
    return local_to_world(g.start, r * std::sin(angle), r * (1.0 - std::cos(angle)), angle);
  }
  Pose2 operator()(const Spiral& sp) const {
    // heading(s) = k0 s + (k1 - k0) s^2 / (2 L); position = integral of (cos, sin) heading.
    const double rate = g.length > 0 ? (sp.curv_end - sp.curv_start) / g.length : 0.0;
    const auto heading = [&](double s) { return sp.curv_start * s + 0.5 * rate * s * s; };
    const double u = integrate([&](double s) { return std::cos(heading(s)); }, 0.0, ds, kPieceLength);
    const double v = integrate([&](double s) { return std::sin(heading(s)); }, 0.0, ds, kPieceLength);
    return local_to_world(g.start, u, v, heading(ds));
  }
  Pose2 operator()(const Poly3& p) const {
    const double u = poly3_u_at(p, ds);
    const double v = p.a + p.b * u + p.c * u * u + p.d * u * u * u;
    const double dv = p.b + 2 * p.c * u + 3 * p.d * u * u;
    return local_to_world(g.start, u, v, std::atan(dv));
  }
  Pose2 operator()(const ParamPoly3& p) const {
    // The parameter p runs linearly with s over the record (as other players read pRange).
    const double t = p.normalized ? (g.length > 0 ? ds / g.length : 0.0) : ds;
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
  double operator()(const Line&) const { return 0.0; }
  double operator()(const Arc& a) const { return a.curvature; }
  double operator()(const Spiral& sp) const {
    return g.length > 0 ? sp.curv_start + (sp.curv_end - sp.curv_start) * ds / g.length : sp.curv_start;
  }
  double operator()(const Poly3& p) const {
    const double u = poly3_u_at(p, ds);
    const double dv = p.b + 2 * p.c * u + 3 * p.d * u * u;
    const double ddv = 2 * p.c + 6 * p.d * u;
    return ddv / std::pow(1.0 + dv * dv, 1.5);
  }
  double operator()(const ParamPoly3& p) const {
    const double t = p.normalized ? (g.length > 0 ? ds / g.length : 0.0) : ds;
    const double du = p.bu + 2 * p.cu * t + 3 * p.du * t * t;
    const double dv = p.bv + 2 * p.cv * t + 3 * p.dv * t * t;
    const double ddu = 2 * p.cu + 6 * p.du * t;
    const double ddv = 2 * p.cv + 6 * p.dv * t;
    const double speed = std::hypot(du, dv);
    return speed > 0 ? (du * ddv - dv * ddu) / (speed * speed * speed) : 0.0;
  }
};

}  // namespace

Pose2 evaluate(const Geometry& geometry, double ds) {
  return std::visit(Evaluator{std::clamp(ds, 0.0, geometry.length), geometry}, geometry.shape);
}

double curvature(const Geometry& geometry, double ds) {
  return std::visit(CurvatureOf{std::clamp(ds, 0.0, geometry.length), geometry}, geometry.shape);
}

PlanView::PlanView(std::vector<Geometry> geometries) : geometries_(std::move(geometries)) {
  std::stable_sort(geometries_.begin(), geometries_.end(),
                   [](const Geometry& a, const Geometry& b) { return a.s < b.s; });
}

double PlanView::length() const {
  if (geometries_.empty()) return 0.0;
  return geometries_.back().s + geometries_.back().length;
}

const Geometry& PlanView::record_at(double s) const {
  // The last record starting at or before s.
  auto it = std::upper_bound(geometries_.begin(), geometries_.end(), s,
                             [](double value, const Geometry& g) { return value < g.s; });
  if (it != geometries_.begin()) --it;
  return *it;
}

Pose2 PlanView::pose(double s) const {
  if (geometries_.empty()) return {};
  const Geometry& g = record_at(s);
  return evaluate(g, s - g.s);
}

double PlanView::curvature(double s) const {
  if (geometries_.empty()) return 0.0;
  const Geometry& g = record_at(s);
  return opendrive::curvature(g, s - g.s);
}

}  // namespace orch::opendrive
