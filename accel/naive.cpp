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

std::optional<Hit> NaiveAccelerator::closest_hit(const Ray& ray) const { return closest_hit(ray, NoHitFilter{}); }

bool NaiveAccelerator::any_hit(const Ray& ray) const { return any_hit(ray, NoHitFilter{}); }

}  // namespace kappa
