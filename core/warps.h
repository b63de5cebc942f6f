// Warps and frames shared by the path tracer and the BSDFs (renderer/bsdf/):
// a shading frame about a normal, cosine-weighted hemisphere sampling and
// luminance. On the ground floor so that the BSDFs need nothing above it.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/vec3.h"

namespace kappa {

/// Orthonormal basis around a unit vector n (Duff et al. 2017, branchless).
struct Frame {
  Vec3f s, t, n;

  explicit Frame(const Vec3f& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
  }
  Vec3f to_world(const Vec3f& v) const { return s * v.x + t * v.y + n * v.z; }
  Vec3f to_local(const Vec3f& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

/// Cosine-weighted direction about +z (Malley's method on a concentric disk).
inline Vec3f sample_cosine_hemisphere(float u1, float u2) {
  const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  float r = 0, phi = 0;
  if (a != 0.0f || b != 0.0f) {
    constexpr float kPi4 = std::numbers::pi_v<float> / 4.0f;
    if (std::abs(a) > std::abs(b)) {
      r = a;
      phi = kPi4 * (b / a);
    } else {
      r = b;
      phi = 2.0f * kPi4 - kPi4 * (a / b);
    }
  }
  const float x = r * std::cos(phi), y = r * std::sin(phi);
  return {x, y, std::sqrt(std::max(0.0f, 1.0f - x * x - y * y))};
}

inline float cosine_hemisphere_pdf(float cos_theta) {
  return cos_theta > 0.0f ? cos_theta * std::numbers::inv_pi_v<float> : 0.0f;
}

inline float luminance(const Vec3f& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace kappa
