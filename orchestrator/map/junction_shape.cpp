#include "map/junction_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace orch {

namespace {

// The arc lengths along `lane` where the closed polygon `shape` crosses it.
std::vector<double> crossings(const std::vector<Vec2>& shape, const Polyline& lane) {
  std::vector<double> out;
  const auto& pts = lane.points();
  for (std::size_t k = 0; k < shape.size(); ++k) {
    const Vec2& a = shape[k];
    const Vec2& b = shape[(k + 1) % shape.size()];
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const Vec2 r = pts[i + 1] - pts[i];
      const Vec2 q = b - a;
      const double den = r.x() * q.y() - r.y() * q.x();
      if (std::abs(den) < 1e-12) continue;  // parallel: touching along a line is no cut
      const Vec2 w = a - pts[i];
      const double t = (w.x() * q.y() - w.y() * q.x()) / den;
      const double u = (w.x() * r.y() - w.y() * r.x()) / den;
      if (t < -1e-9 || t > 1 + 1e-9 || u < -1e-9 || u > 1 + 1e-9) continue;
      out.push_back(lane.s_at_index(i) + t * (lane.s_at_index(i + 1) - lane.s_at_index(i)));
    }
  }
  return out;
}

}  // namespace

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Andrew's monotone chain, counter-clockwise, without collinear points.
std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (pts.size() < 3) return pts;
  std::vector<Vec2> hull(2 * pts.size());
  std::size_t k = 0;
  for (const Vec2& p : pts) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 1e-9) --k;
    hull[k++] = p;
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 1e-9) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

// The lane-end corners in the order of their angle around the centre: a polygon whose
// boundary runs across each lane's end between its two corners, so it touches every lane
// at its end only (a convex hull would reach over lanes that end further out and make
// netconvert cut them short).
std::vector<Vec2> star_polygon(std::vector<Vec2> corners, const Vec2& centre) {
  std::stable_sort(corners.begin(), corners.end(), [&](const Vec2& a, const Vec2& b) {
    return std::atan2(a.y() - centre.y(), a.x() - centre.x()) < std::atan2(b.y() - centre.y(), b.x() - centre.x());
  });
  return corners;
}




// How far `shape` cuts into lane end `e` (m). A lane lying wholly inside the shape (a short
// dead-end lane inside its junction) crosses it nowhere, and netconvert moves it to a
// stub of 0.2 m: that is a cut of the whole lane.
double cut_into(const std::vector<Vec2>& shape, const LaneEnd& e) {
  double cut = 0;
  for (const double s : crossings(shape, *e.shape)) cut = std::max(cut, e.incoming ? e.shape->length() - s : s);
  if (cut <= kMaxShapeCut && shape.size() >= 3) {
    const double length = e.shape->length();
    const double probe = std::min(0.5, length / 2);
    if (inside_polygon(e.shape->point_at(e.incoming ? length - probe : probe), shape)) cut = length;
  }
  return cut > kMaxShapeCut ? cut : 0.0;
}

// How much of the lanes `shape` would cut off (m, summed).
double cut_length(const std::vector<Vec2>& shape, const std::vector<LaneEnd>& ends) {
  double sum = 0;
  for (const LaneEnd& e : ends) sum += cut_into(shape, e);
  return sum;
}

// `pts` as a polygon with no area (there and back), so that netconvert closes no other edge.
std::vector<Vec2> there_and_back(std::vector<Vec2> pts) {
  const std::size_t n = pts.size();
  for (std::size_t i = n - 1; i-- > 1;) pts.push_back(pts[i]);
  return pts;
}


namespace {

// uncut_tree with a grid reaching `margin` beyond the tree's terminals; `too_large` says that
// grid would have more than kMaxTreeGridPoints points (no larger one is tried then).
std::vector<Vec2> uncut_tree_within(std::vector<TreeNode> nodes, const std::vector<LaneEnd>& ends, double margin,
                                    bool& too_large) {
  const std::size_t terminals = nodes.size();
  if (terminals < 2) return {};
  const auto clear = [&](const Vec2& a, const Vec2& b) {
    if ((a - b).norm() < 1e-9) return false;
    const std::vector<Vec2> seg{a, b};
    return std::none_of(ends.begin(), ends.end(), [&](const LaneEnd& e) { return cut_into(seg, e) > 0; });
  };
  std::vector<bool> in(terminals, false);
  std::vector<std::vector<std::size_t>> children(terminals);
  // Corner pairs are joined at once: the segment across a lane end is the lane end itself.
  const auto join = [&](const auto& self, std::size_t child, std::size_t par) -> void {
    in[child] = true;
    children[par].push_back(child);
    for (const std::size_t q : nodes[child].partners)
      if (!in[q]) self(self, q, child);
  };
  in[0] = true;
  for (const std::size_t q : nodes[0].partners)
    if (!in[q]) join(join, q, 0);
  const auto connected = [&] { return std::all_of(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(terminals), [](bool b) { return b; }); };
  bool grid = false;
  while (!connected()) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t bu = 0;
    std::size_t bv = 0;
    for (std::size_t u = 0; u < nodes.size(); ++u) {
      if (!in[u]) continue;
      for (std::size_t v = 0; v < terminals; ++v) {
        if (in[v]) continue;
        const double d = (nodes[u].p - nodes[v].p).norm();
        if (d < best && clear(nodes[u].p, nodes[v].p)) {
          best = d;
          bu = u;
          bv = v;
        }
      }
    }
    if (std::isfinite(best)) {
      join(join, bv, bu);
      continue;
    }
    // No straight segment reaches the rest (a lane curving between them): around the lanes,
    // through a grid of points over the junction, shortest path first (Dijkstra).
    if (!grid) {
      grid = true;
      Vec2 lo = nodes[0].p;
      Vec2 hi = nodes[0].p;
      for (std::size_t k = 0; k < terminals; ++k) {
        lo = lo.cwiseMin(nodes[k].p);
        hi = hi.cwiseMax(nodes[k].p);
      }
      lo -= Vec2(margin, margin);
      hi += Vec2(margin, margin);
      const auto cells = [&](double span) { return static_cast<int>(std::ceil(span / kTreeGridStep)); };
      if (static_cast<long long>(cells(hi.x() - lo.x()) + 1) * (cells(hi.y() - lo.y()) + 1) > kMaxTreeGridPoints) {
        too_large = true;
        return {};
      }
      for (int i = 0; i <= cells(hi.x() - lo.x()); ++i)
        for (int j = 0; j <= cells(hi.y() - lo.y()); ++j)
          nodes.push_back({lo + Vec2(i * kTreeGridStep, j * kTreeGridStep), {}});
      in.resize(nodes.size(), false);
      children.resize(nodes.size());
    }
    const std::size_t n = nodes.size();
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    std::vector<std::size_t> prev(n, n);
    std::vector<bool> done(n, false);
    for (std::size_t u = 0; u < n; ++u)
      if (in[u]) dist[u] = 0;
    std::size_t reached = n;
    for (;;) {
      std::size_t u = n;
      for (std::size_t k = 0; k < n; ++k)
        if (!done[k] && std::isfinite(dist[k]) && (u == n || dist[k] < dist[u])) u = k;
      if (u == n) break;
      done[u] = true;
      if (!in[u] && u < terminals) {
        reached = u;
        break;
      }
      for (std::size_t v = 0; v < n; ++v) {
        if (done[v] || in[v]) continue;
        const double d = (nodes[u].p - nodes[v].p).norm();
        if (d > kTreeGridReach || dist[u] + d >= dist[v] || !clear(nodes[u].p, nodes[v].p)) continue;
        dist[v] = dist[u] + d;
        prev[v] = u;
      }
    }
    if (reached == n) return {};
    std::vector<std::size_t> path;
    for (std::size_t v = reached; !in[v]; v = prev[v]) path.push_back(v);
    std::size_t par = prev[path.back()];
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      join(join, *it, par);
      par = *it;
    }
  }
  std::vector<Vec2> tour;
  const auto walk = [&](const auto& self, std::size_t u) -> void {
    tour.push_back(nodes[u].p);
    for (const std::size_t c : children[u]) {
      self(self, c);
      tour.push_back(nodes[u].p);
    }
  };
  walk(walk, 0);
  tour.pop_back();  // back at the root: netconvert closes the polygon
  return tour;
}

}  // namespace

std::vector<Vec2> uncut_tree(std::vector<TreeNode> nodes, const std::vector<LaneEnd>& ends) {
  // The grid reaches farther out only where a nearer one finds no way round: a lane that
  // bends back between the lane ends (seed 831: a lane turning away from its road mid-block
  // in a U, its end 40 m from its neighbour's, the way round 28 m beyond both).
  for (const double margin : kTreeGridMargins) {
    bool too_large = false;
    std::vector<Vec2> tree = uncut_tree_within(nodes, ends, margin, too_large);
    if (!tree.empty() || too_large) return tree;
  }
  return {};
}

}  // namespace orch
