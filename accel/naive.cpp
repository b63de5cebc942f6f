#include "naive.h"

namespace kappa {

std::optional<Hit> NaiveAccelerator::closest_hit(const Ray& ray) const {
  const PreparedRay prepared(ray);
  Hit best;
  best.t = ray.tmax;
  const auto n = static_cast<TriangleId>(m_triangles.size());
  for (TriangleId i = 0; i < n; ++i) test_closest(prepared, m_triangles[i], i, ray.tmin, best);
  if (!best.valid()) return std::nullopt;
  return best;
}

bool NaiveAccelerator::any_hit(const Ray& ray) const {
  const PreparedRay prepared(ray);
  float t, b0, b1, b2;
  for (const Triangle& tri : m_triangles) {
    if (intersect_triangle(prepared, tri, ray.tmin, ray.tmax, t, b0, b1, b2)) return true;
  }
  return false;
}

}  // namespace kappa
