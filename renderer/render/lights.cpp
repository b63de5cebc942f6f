#include "renderer/render/lights.h"

#include <algorithm>
#include <numbers>

#include "renderer/render/sampling.h"

namespace kappa {

Lights::Lights(const Scene& scene) {
  std::vector<double> power;
  for (TriangleId i = 0; i < TriangleId(scene.triangles.size()); ++i) {
    const Material& m = scene.materials[scene.material_of[i]];
    if (!m.emissive()) continue;
    const double area = 0.5 * double_area(scene.triangles[i]);
    // One-sided emitter: power = L * area * pi (luminance in double, so a
    // tiny but positive Ke is still a light); twice that for both sides.
    // An emission map's power is its mean texel's (Blender's map_Ke replaces Ke).
    const std::int32_t map = m.maps[std::size_t(MapSlot::emission)];
    const Vec3d Ke(map >= 0 ? scene.texture_maps[std::size_t(map)].mean : m.emission);
    const double p = (0.2126 * Ke.x + 0.7152 * Ke.y + 0.0722 * Ke.z) * area * std::numbers::pi *
                     (m.emits_both_sides ? 2.0 : 1.0);
    if (!(p > 0)) continue;
    m_triangles.push_back(i);
    m_areas.push_back(float(area));
    power.push_back(p);
  }
  // A constant environment around a scene of bounding radius R: power
  // 4 pi * pi R^2 * L, as pbrt-v4's UniformInfiniteLight::Phi.
  const Bounds3f b = scene.bounds();
  const double radius = b.empty() ? 0.0 : 0.5 * length(Vec3d(b.diagonal()));
  const double env_power = double(luminance(scene.environment)) * 4.0 * std::numbers::pi * std::numbers::pi *
                           std::max(radius * radius, 1e-30);
  power.push_back(scene.environment == Vec3f{0, 0, 0} ? 0.0 : env_power);
  // Punctual lights, as pbrt-v4's Phi: a point light 4 pi I, a spot light
  // 2 pi I (1 - (cos_inner + cos_outer) / 2), a directional light pi R^2 E.
  for (const PunctualLight& l : scene.punctual_lights) {
    const double I = double(luminance(l.intensity));
    switch (l.type) {
      case PunctualLight::Type::point: power.push_back(4.0 * std::numbers::pi * I); break;
      case PunctualLight::Type::spot:
        power.push_back(2.0 * std::numbers::pi * I * (1.0 - 0.5 * (double(l.cos_inner) + double(l.cos_outer))));
        break;
      case PunctualLight::Type::directional:
        power.push_back(std::numbers::pi * std::max(radius * radius, 1e-30) * I);
        break;
    }
  }
  m_punctual_count = scene.punctual_lights.size();

  double total = 0;
  for (double p : power) total += p;
  if (!(total > 0)) {
    m_triangles.clear();
    m_areas.clear();
    return;  // no lights: no next-event estimation
  }
  double running = 0;
  for (double p : power) {
    running += p / total;
    m_cdf.push_back(running);
  }
  m_cdf.back() = 1.0;
  // Each light's probability is its step of the cdf choose() reads, so a
  // light has pmf 0 exactly when choose() can never pick it (nee then counts
  // it where BSDF sampling finds it instead).
  for (std::size_t i = 0; i < m_cdf.size(); ++i) m_pmf.push_back(float(m_cdf[i] - (i > 0 ? m_cdf[i - 1] : 0.0)));
  m_pmf_environment = m_pmf[environment_index()];
  if (!m_triangles.empty()) {
    m_pmf_of_triangle.assign(scene.triangles.size(), 0.0f);
    m_area_of_triangle.assign(scene.triangles.size(), 0.0f);
    for (std::size_t l = 0; l < m_triangles.size(); ++l) {
      m_pmf_of_triangle[m_triangles[l]] = m_pmf[l];
      m_area_of_triangle[m_triangles[l]] = m_areas[l];
    }
  }
}

std::size_t Lights::choose(double u) const {
  const auto it = std::upper_bound(m_cdf.begin(), m_cdf.end(), u);
  std::size_t i = std::min<std::size_t>(std::size_t(it - m_cdf.begin()), m_cdf.size() - 1);
  while (m_pmf[i] == 0.0f && i > 0) --i;  // never return a zero-probability light
  return i;
}

}  // namespace kappa
