// Predictions of the seed paper's cost model for a uniform grid, in their
// per-axis forms for non-cubic cells (see ../shared/paper/NOTES.md):
//   eq 19: expected multiplicity of one object from its projections;
//   eq 21: the same for randomly oriented objects, from D, SA and V;
//   eq 22: the probability that a uniform random line through the grid box
//          meets a cell, SA(c_i) / SA(V), summed over cells for p_tot;
//   eq 24: expected cells met by a segment placed at random.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "accel/recorder.h"
#include "accel/triangle.h"
#include "core/vec3.h"

namespace kappa {

/// Theta_tot expected over random grid offsets, eq 19 summed over the
/// triangles: sum_j 1 + sum_a L_a(o_j)/l_a + sum_{a<b} A_ab(o_j)/(l_a l_b),
/// where L_a is the extent of the triangle along axis a and A_ab the area of
/// its projection onto the a-b plane (V = 0 for triangles).
double theta_tot_eq19(std::span<const Triangle> triangles, const Vec3d& cell);

/// eq 21 in per-axis form: N + D(O) sum_a 1/l_a + SA(O)/4 sum_{a<b} 1/(l_a l_b),
/// with D(O) = sum of perimeters / 4 (Cauchy: mean projected length of a flat
/// convex set) and SA(O) = sum of 2 * area (both sides), V(O) = 0.
double theta_tot_eq21(std::span<const Triangle> triangles, const Vec3d& cell);

/// eq 22 summed over the N_c cells of a grid with cell sides `cell` tiling a
/// box of sides `box`: p_tot = N_c * SA(cell) / SA(box).
double p_tot_lines_eq22(const Vec3d& box, const Vec3d& cell, double N_c);

/// Expected cells met by a segment of vector v placed at random with respect
/// to the grid: 1 + sum_a |v_a| / l_a (eq 24 per axis; a segment has D = |v|/2).
double cells_for_segment(const Vec3d& v, const Vec3d& cell);

/// The model's cells for the part of a ray a walk covered (accel/recorder.h),
/// in a grid of cells 1/inv_cell: eq 24 per axis, 1 + sum_a |v_a| / l_a for
/// v the walked segment inside the grid box, less 1/2 for each end that lies
/// on the grid box, which is a grid plane (NOTES: eq 24's leading 1 is for
/// random segments; a chord through the whole box, both ends on planes,
/// expects sum_a |v_a| / l_a, eq 22); 0 if that part is empty. Per ray, in
/// stats-on renders: inline.
inline double predicted_cells_eq24(const WalkSegment& s, const Vec3d& inv_cell) {
  const double end = std::min(s.t_out, s.t_end);
  if (!(end > s.t_in)) return 0.0;
  const double len = end - s.t_in;
  const int ends_on_box = int(s.t_in > s.t_min) + int(s.t_out < s.t_end);
  return 1.0 - 0.5 * ends_on_box + std::abs(s.d.x) * len * inv_cell.x + std::abs(s.d.y) * len * inv_cell.y +
         std::abs(s.d.z) * len * inv_cell.z;
}

}  // namespace kappa
