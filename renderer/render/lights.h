// The lights of a scene: its emissive triangles, the environment and glTF's
// punctual lights, chosen for next-event estimation with probability
// proportional to power. Indices: the triangles, then the environment, then
// the punctual lights (a scene without them has the layout it always had).
#pragma once

#include <cstdint>
#include <vector>

#include "accel/ray.h"
#include "renderer/scene/scene.h"

namespace kappa {

class Lights {
 public:
  explicit Lights(const Scene& scene);

  bool empty() const { return m_cdf.empty(); }
  /// Emissive triangles bright enough to be picked (the environment aside).
  std::size_t triangle_count() const { return m_triangles.size(); }

  /// Picks a light from u in [0, 1): the index of an emissive triangle in
  /// `triangle(i)`, or `environment_index()` for the sky.
  std::size_t choose(double u) const;
  std::size_t environment_index() const { return m_triangles.size(); }
  std::size_t punctual_count() const { return m_punctual_count; }
  /// The index in Scene::punctual_lights of light `light`, or -1 when it is
  /// not a punctual light.
  std::ptrdiff_t punctual(std::size_t light) const {
    return light > environment_index() ? std::ptrdiff_t(light - environment_index() - 1) : -1;
  }
  TriangleId triangle(std::size_t light) const { return m_triangles[light]; }
  float area(std::size_t light) const { return m_areas[light]; }

  /// Probability that choose() picks a light: per light index, and looked up by
  /// triangle for emitters hit by BSDF-sampled rays (0 if not emissive).
  float pmf(std::size_t light) const { return m_pmf[light]; }
  float pmf_of_triangle(TriangleId id) const { return m_pmf_of_triangle.empty() ? 0.0f : m_pmf_of_triangle[id]; }
  float pmf_environment() const { return m_pmf_environment; }
  float area_of_triangle(TriangleId id) const { return m_area_of_triangle.empty() ? 0.0f : m_area_of_triangle[id]; }

 private:
  std::vector<TriangleId> m_triangles;  ///< emissive triangles
  std::vector<float> m_areas;           ///< their areas
  std::vector<float> m_pmf;             ///< per light, the environment last
  std::vector<double> m_cdf;            ///< running sum of m_pmf, ends at 1
  std::vector<float> m_pmf_of_triangle;   ///< per scene triangle
  std::vector<float> m_area_of_triangle;  ///< per scene triangle (0 if not emissive)
  float m_pmf_environment = 0;
  std::size_t m_punctual_count = 0;
};

}  // namespace kappa
