#include "naive.h"

#include <chrono>

namespace kappa {

NaiveAccelerator::NaiveAccelerator(std::span<const Triangle> triangles) : m_triangles(triangles) {
  const auto start = std::chrono::steady_clock::now();
  m_usable.reserve(triangles.size());
  for (TriangleId i = 0; i < TriangleId(triangles.size()); ++i)
    if (usable_triangle(triangles[i])) m_usable.push_back(i);
  m_build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::optional<Hit> NaiveAccelerator::closest_hit(const Ray& ray) const {
  const PreparedRay prepared(ray);
  Hit best;
  best.t = ray.tmax;
  for (const TriangleId i : m_usable) test_closest(prepared, m_triangles[i], i, ray.tmin, best);
  if (!best.valid()) return std::nullopt;
  return best;
}

bool NaiveAccelerator::any_hit(const Ray& ray) const {
  const PreparedRay prepared(ray);
  float t, b0, b1, b2;
  for (const TriangleId i : m_usable) {
    if (intersect_triangle(prepared, m_triangles[i], ray.tmin, ray.tmax, t, b0, b1, b2)) return true;
  }
  return false;
}

}  // namespace kappa
