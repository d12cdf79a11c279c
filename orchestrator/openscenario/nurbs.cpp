#include "openscenario/nurbs.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace orch::openscenario {
namespace {

// Cox-de Boor: N_i,k(u) over half-open spans [t_i, t_i+1).
double basis(double u, std::size_t i, int k, const std::vector<double>& t) {
  if (k == 1) return t[i] <= u && u < t[i + 1] ? 1.0 : 0.0;
  const auto ku = static_cast<std::size_t>(k);
  const double left_span = t[i + ku - 1] - t[i];
  const double right_span = t[i + ku] - t[i + 1];
  double value = 0;
  if (left_span > 0) value += (u - t[i]) / left_span * basis(u, i, k - 1, t);
  if (right_span > 0) value += (t[i + ku] - u) / right_span * basis(u, i + 1, k - 1, t);
  return value;
}

void check(const std::vector<NurbsControl>& controls, const std::vector<double>& knots, int order) {
  if (order < 1) throw MapError(fmt::format("a Nurbs of order {}: the order must be at least 1", order));
  const auto k = static_cast<std::size_t>(order);
  if (controls.size() < k)
    throw MapError(fmt::format("a Nurbs of order {} needs at least {} control points, it has {}", order, order,
                               controls.size()));
  if (knots.size() != controls.size() + k)
    throw MapError(fmt::format("a Nurbs of order {} with {} control points needs {} knots, it has {}", order,
                               controls.size(), controls.size() + k, knots.size()));
  for (std::size_t i = 1; i < knots.size(); ++i)
    if (knots[i] < knots[i - 1]) throw MapError(fmt::format("Nurbs knot {} is smaller than the one before", i + 1));
  for (std::size_t i = 0; i < controls.size(); ++i)
    if (!(controls[i].weight > 0)) throw MapError(fmt::format("Nurbs control point {} has a weight <= 0", i + 1));
  if (!(knots[controls.size()] > knots[k - 1])) throw MapError("a Nurbs whose knots leave no span to draw");
}

}  // namespace

std::vector<PathPoint> nurbs_points(const std::vector<NurbsControl>& controls, const std::vector<double>& knots,
                                    int order) {
  check(controls, knots, order);
  const std::size_t n = controls.size();
  const double u0 = knots[static_cast<std::size_t>(order) - 1];
  const double u1 = knots[n];
  double polygon = 0;
  for (std::size_t i = 1; i < n; ++i)
    polygon += std::hypot(controls[i].x - controls[i - 1].x, controls[i].y - controls[i - 1].y);
  const int pieces = std::clamp(static_cast<int>(std::ceil(polygon / kClothoidStep)), 2, 1 << 16);
  // The end of the last span is outside its half-open interval: evaluated just inside it.
  const double inside = 1e-9 * (u1 - u0);
  std::vector<PathPoint> points;
  std::vector<double> params;
  std::vector<double> peak_value(n, -1.0), peak_u(n, u0);
  std::vector<double> weights(n);
  for (int step = 0; step <= pieces; ++step) {
    const double u = std::min(u0 + (u1 - u0) * step / pieces, u1 - inside);
    double total = 0, x = 0, y = 0, z = 0;
    for (std::size_t i = 0; i < n; ++i) {
      weights[i] = basis(u, i, order, knots);
      total += weights[i] * controls[i].weight;
      if (weights[i] > peak_value[i]) {
        peak_value[i] = weights[i];
        peak_u[i] = u;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      x += weights[i] * controls[i].weight * controls[i].x / total;
      y += weights[i] * controls[i].weight * controls[i].y / total;
      z += weights[i] * controls[i].weight * controls[i].z.value_or(0.0) / total;
    }
    points.push_back({x, y, 0.0, std::nullopt, std::nullopt,
                      controls.front().z ? std::optional<double>(z) : std::nullopt});
    params.push_back(u);
  }
  if (controls.front().time && n >= 2) {
    // Linear in u between the peaks of consecutive control points (before the first peak:
    // the first time; after the last: the last).
    std::size_t c = 0;
    for (std::size_t j = 0; j < points.size(); ++j) {
      while (c + 2 < n && params[j] >= peak_u[c + 1]) ++c;
      const double span = peak_u[c + 1] - peak_u[c];
      const double f = span > 0 ? std::clamp((params[j] - peak_u[c]) / span, 0.0, 1.0) : 1.0;
      points[j].due = *controls[c].time + f * (*controls[c + 1].time - *controls[c].time);
    }
  }
  return points;
}

}  // namespace orch::openscenario
