// The Trowbridge-Reitz (GGX) microfacet distribution, isotropic: its normal
// distribution D, Smith's height-correlated masking-shadowing G, and sampling
// of the visible normals (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals"), as pbrt-v4's TrowbridgeReitzDistribution.
// alpha = roughness^2 (glTF 2.0, Blender's Principled BSDF).
#pragma once

#include <cmath>
#include <numbers>

#include "renderer/bsdf/local_frame.h"

namespace kappa::bsdf {

/// Below this alpha a microfacet lobe is a delta lobe (a smooth mirror or
/// glass): its D would overflow float, and pbrt-v4 draws the same line
/// (EffectivelySmooth). roughness < 0.0316.
inline constexpr float kSmoothAlpha = 1e-3f;

class Ggx {
 public:
  explicit Ggx(float alpha) : m_alpha(alpha) {}

  float alpha() const { return m_alpha; }
  bool smooth() const { return m_alpha < kSmoothAlpha; }

  /// D(wm): microfacet normals' density per projected area.
  float D(const Vec3f& wm) const {
    const float c2 = cos2_theta(wm);
    const float cos4 = c2 * c2;
    if (cos4 < 1e-16f) return 0.0f;
    const float t2 = sin2_theta(wm) / c2;
    const float e = t2 / (m_alpha * m_alpha);
    return 1.0f / (std::numbers::pi_v<float> * m_alpha * m_alpha * cos4 * (1.0f + e) * (1.0f + e));
  }

  /// Smith's auxiliary function Lambda(w).
  float lambda(const Vec3f& w) const {
    const float c2 = cos2_theta(w);
    if (c2 == 0.0f) return 0.0f;  // grazing: G is 0 through the other terms
    const float t2 = sin2_theta(w) / c2;
    return 0.5f * (std::sqrt(1.0f + m_alpha * m_alpha * t2) - 1.0f);
  }

  float G1(const Vec3f& w) const { return 1.0f / (1.0f + lambda(w)); }
  /// Height-correlated masking-shadowing (Heitz 2014, eq. 99).
  float G(const Vec3f& wo, const Vec3f& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

  /// The distribution of normals visible from w: G1(w) max(0, w.wm) D(wm) / cos(w).
  float D_visible(const Vec3f& w, const Vec3f& wm) const {
    const float c = abs_cos_theta(w);
    if (c == 0.0f) return 0.0f;
    return G1(w) / c * D(wm) * std::abs(dot(w, wm));
  }

  /// A visible normal from w (any side; the normal is on +z), from u in [0, 1)^2.
  Vec3f sample_visible(const Vec3f& w, float u1, float u2) const {
    Vec3f wh = normalize(Vec3f{m_alpha * w.x, m_alpha * w.y, w.z});
    if (wh.z < 0.0f) wh = -wh;
    const Vec3f t1 = wh.z < 0.99999f ? normalize(cross(Vec3f{0, 0, 1}, wh)) : Vec3f{1, 0, 0};
    const Vec3f t2 = cross(wh, t1);
    // A uniform point on the disk, its upper part stretched to the projected hemisphere.
    const float r = std::sqrt(u1), phi = 2.0f * std::numbers::pi_v<float> * u2;
    float px = r * std::cos(phi), py = r * std::sin(phi);
    const float h = std::sqrt(std::max(0.0f, 1.0f - px * px));
    const float s = 0.5f * (1.0f + wh.z);
    py = (1.0f - s) * h + s * py;
    const float pz = std::sqrt(std::max(0.0f, 1.0f - px * px - py * py));
    const Vec3f nh = t1 * px + t2 * py + wh * pz;
    return normalize(Vec3f{m_alpha * nh.x, m_alpha * nh.y, std::max(1e-6f, nh.z)});
  }

 private:
  float m_alpha;
};

}  // namespace kappa::bsdf
