// Triangle / axis-aligned box overlap by the separating axis theorem
// (Akenine-Möller 2001, "Fast 3D Triangle-Box Overlap Testing"), in double
// precision. Closed boxes: a triangle that only touches the box (a face, an
// edge or a vertex) overlaps it, so nothing lying exactly on a cell boundary
// can fall out of every cell through rounding.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace kappa {

namespace detail {

/// True if the projections of the triangle (a, b, c, relative to the box
/// centre) and of the box (half sizes h) onto `axis` are disjoint.
inline bool separated_on(const Vec3d& axis, const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& h) {
  const double pa = dot(axis, a), pb = dot(axis, b), pc = dot(axis, c);
  const double r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
  const double lo = std::min({pa, pb, pc}), hi = std::max({pa, pb, pc});
  return lo > r || hi < -r;
}

}  // namespace detail

/// True if triangle (v0, v1, v2) and the closed box [lo, hi] share a point.
inline bool triangle_overlaps_box(const Vec3d& v0, const Vec3d& v1, const Vec3d& v2, const Vec3d& lo, const Vec3d& hi) {
  const Vec3d center = (lo + hi) * 0.5;
  const Vec3d h = (hi - lo) * 0.5;
  const Vec3d a = v0 - center, b = v1 - center, c = v2 - center;

  // The box's own axes: the triangle's bounding box against the box.
  for (int k = 0; k < 3; ++k) {
    const double mn = std::min({a[k], b[k], c[k]}), mx = std::max({a[k], b[k], c[k]});
    if (mn > h[k] || mx < -h[k]) return false;
  }
  // The triangle's plane.
  const Vec3d e0 = b - a, e1 = c - b, e2 = a - c;
  const Vec3d n = cross(e0, e1);
  if (detail::separated_on(n, a, b, c, h)) return false;
  // The nine edge x box-axis directions. A zero axis (edge parallel to a box
  // axis) separates nothing: its projections are all 0 and r is 0, so the
  // test correctly reports overlap.
  const Vec3d edges[3] = {e0, e1, e2};
  const Vec3d axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Vec3d& e : edges) {
    for (const Vec3d& u : axes) {
      if (detail::separated_on(cross(u, e), a, b, c, h)) return false;
    }
  }
  return true;
}

}  // namespace kappa
