// Which cells of the uniform grid a triangle goes in, found slab by slab so
// the work grows with the cells the triangle touches, not with its bounding
// box: a triangle across a 68^3 grid touches about 9,000 of the 314,000
// cells of its box.
//
// The separating-axis test still decides every cell. The slabs only narrow
// the candidates: for each z slab the triangle is clipped to that slab, its
// bounds give the y rows to try; each row clips again and gives the x cells.
// Clipping slabs and candidate ranges reach twice the insertion margin past
// each cell: the margin (32 float ulps of the scene's size, about 4e-6 of
// it) dwarfs the rounding of the clip and of the range arithmetic (about
// 1e-15 of it), so no cell the test would accept is ever skipped and every
// cell holds exactly the triangles it held when the whole box was tested.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "grid.h"
#include "triangle_box.h"

namespace kappa {

namespace detail {

/// A convex polygon on the stack. A triangle clipped by two slabs has at
/// most 3 + 2 + 2 distinct vertices, but a vertex lying exactly on a plane
/// is emitted again as its own crossing, and rounding may bend the polygon:
/// room for the worst case of every edge giving three points, twice.
struct ClipPolygon {
  Vec3d v[27];
  int n = 0;
};

/// The part of `p` with lo <= coordinate `axis` <= hi (Sutherland-Hodgman
/// against the slab's two planes at once: an edge crossing the whole slab
/// gives both crossings).
inline void clip_to_slab(const ClipPolygon& p, int axis, double lo, double hi, ClipPolygon& out) {
  out.n = 0;
  auto crossing = [axis](const Vec3d& a, const Vec3d& b, double plane) {
    const double t = (plane - a[axis]) / (b[axis] - a[axis]);  // a and b lie on opposite sides: no 0/0
    Vec3d c = a + (b - a) * t;
    (axis == 0 ? c.x : axis == 1 ? c.y : c.z) = plane;
    return c;
  };
  for (int i = 0; i < p.n; ++i) {
    const Vec3d& a = p.v[i];
    const Vec3d& b = p.v[(i + 1) % p.n];
    const double ca = a[axis], cb = b[axis];
    if (ca >= lo && ca <= hi) out.v[out.n++] = a;
    // Leaving or entering through the low plane, then through the high one,
    // in the order met going from a to b.
    const bool cross_lo = (ca < lo) != (cb < lo), cross_hi = (ca > hi) != (cb > hi);
    if (cross_lo && cross_hi) {
      const bool rising = cb > ca;
      out.v[out.n++] = crossing(a, b, rising ? lo : hi);
      out.v[out.n++] = crossing(a, b, rising ? hi : lo);
    } else if (cross_lo) {
      out.v[out.n++] = crossing(a, b, lo);
    } else if (cross_hi) {
      out.v[out.n++] = crossing(a, b, hi);
    }
  }
}

/// Candidate cell range [first, last] along `axis` for polygon `p`: the
/// cells whose extent, widened by twice the margin, meets the polygon's
/// (closed: a cell touching it exactly is in); empty (first > last) for no
/// polygon.
inline void candidate_range(const GridInfo& grid, const Vec3d& inv_cell, const ClipPolygon& p, int axis, int& first,
                            int& last) {
  double mn = INFINITY, mx = -INFINITY;
  for (int i = 0; i < p.n; ++i) {
    mn = std::min(mn, p.v[i][axis]);
    mx = std::max(mx, p.v[i][axis]);
  }
  if (p.n == 0) {
    first = 1, last = 0;
    return;
  }
  const double n = double(grid.resolution[axis] - 1);
  const double reach = 2.0 * grid.margin * inv_cell[axis];
  first = int(std::clamp(std::floor((mn - grid.lo[axis]) * inv_cell[axis] - reach), 0.0, n));
  last = int(std::clamp(std::floor((mx - grid.lo[axis]) * inv_cell[axis] + reach), 0.0, n));
}

/// Cell k's extent along `axis` (the last cell ends exactly at the box).
inline double cell_lo(const GridInfo& grid, int axis, int k) { return grid.lo[axis] + k * grid.cell_size[axis]; }
inline double cell_hi(const GridInfo& grid, int axis, int k) {
  return k + 1 == grid.resolution[axis] ? grid.hi[axis] : cell_lo(grid, axis, k) + grid.cell_size[axis];
}

}  // namespace detail

/// Every cell: the filter of a whole grid's build.
struct EveryCell {
  constexpr bool operator()(std::uint64_t) const { return true; }
};

/// Calls f(cell index) for every cell of `grid` that `keep` accepts and whose
/// closed box, inflated by the margin, triangle t overlaps, in increasing x
/// within y within z; a cell `keep` refuses costs no separating-axis test.
/// Returns the number of separating-axis tests made.
template <typename F, typename Keep = EveryCell>
std::uint64_t for_each_overlapped_cell(const GridInfo& grid, const Vec3d& inv_cell, const Triangle& t, F&& f,
                                       Keep&& keep = {}) {
  using detail::cell_hi;
  using detail::cell_lo;
  const Vec3d v0(t.v0), v1(t.v1), v2(t.v2);
  const double m = grid.margin;
  const Vec3d margin{m, m, m};
  detail::ClipPolygon whole;
  whole.v[0] = v0, whole.v[1] = v1, whole.v[2] = v2, whole.n = 3;
  detail::ClipPolygon slab_clip, row_clip;
  std::uint64_t tests = 0;
  int z0, z1;
  detail::candidate_range(grid, inv_cell, whole, 2, z0, z1);
  for (int z = z0; z <= z1; ++z) {
    // One slab (or row) of candidates needs no clip: the unclipped polygon's
    // ranges hold the clipped one's, and the test decides every candidate, so
    // the cells found are the same (most triangles of a fine sub-grid).
    const detail::ClipPolygon* slab = &whole;
    if (z0 != z1) {
      detail::clip_to_slab(whole, 2, cell_lo(grid, 2, z) - 2 * m, cell_hi(grid, 2, z) + 2 * m, slab_clip);
      slab = &slab_clip;
    }
    int y0, y1;
    detail::candidate_range(grid, inv_cell, *slab, 1, y0, y1);
    for (int y = y0; y <= y1; ++y) {
      const detail::ClipPolygon* row = slab;
      if (y0 != y1) {
        detail::clip_to_slab(*slab, 1, cell_lo(grid, 1, y) - 2 * m, cell_hi(grid, 1, y) + 2 * m, row_clip);
        row = &row_clip;
      }
      int x0, x1;
      detail::candidate_range(grid, inv_cell, *row, 0, x0, x1);
      const std::uint64_t row_index =
          std::uint64_t(grid.resolution.nx) * (std::uint64_t(y) + std::uint64_t(grid.resolution.ny) * std::uint64_t(z));
      for (int x = x0; x <= x1; ++x) {
        const std::uint64_t index = std::uint64_t(x) + row_index;
        if (!keep(index)) continue;
        ++tests;
        const Vec3d lo{cell_lo(grid, 0, x), cell_lo(grid, 1, y), cell_lo(grid, 2, z)};
        const Vec3d hi{cell_hi(grid, 0, x), cell_hi(grid, 1, y), cell_hi(grid, 2, z)};
        if (triangle_overlaps_box(v0, v1, v2, lo - margin, hi + margin)) f(index);
      }
    }
  }
  return tests;
}

}  // namespace kappa
