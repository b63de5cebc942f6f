#include "cost_model.h"

#include "accel/grid.h"

#include <algorithm>
#include <cmath>

namespace kappa {

double theta_tot_eq19(std::span<const Triangle> triangles, const Vec3d& l) {
  return OccupancyModel(triangles).theta_tot(l);
}

double theta_tot_eq21(std::span<const Triangle> triangles, const Vec3d& l) {
  double N = 0, D = 0, SA = 0;
  for (const Triangle& t : triangles) {
    if (!usable_triangle(t)) continue;
    const Vec3d a(t.v0), b(t.v1), c(t.v2);
    N += 1;
    D += (length(b - a) + length(c - b) + length(a - c)) / 4.0;
    SA += length(cross(b - a, c - a));  // 2 * area: both sides
  }
  return N + D * (1 / l.x + 1 / l.y + 1 / l.z) + SA / 4.0 * (1 / (l.y * l.z) + 1 / (l.x * l.z) + 1 / (l.x * l.y));
}

double p_tot_lines_eq22(const Vec3d& box, const Vec3d& l, double N_c) {
  const double sa_cell = 2 * (l.x * l.y + l.y * l.z + l.z * l.x);
  const double sa_box = 2 * (box.x * box.y + box.y * box.z + box.z * box.x);
  return sa_box > 0 ? N_c * sa_cell / sa_box : 0.0;
}

double cells_for_segment(const Vec3d& v, const Vec3d& l) {
  return 1.0 + std::abs(v.x) / l.x + std::abs(v.y) / l.y + std::abs(v.z) / l.z;
}

}  // namespace kappa
