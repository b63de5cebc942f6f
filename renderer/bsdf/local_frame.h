// The shading frame's conventions, shared by every lobe: directions are unit
// vectors in a local frame whose +z is the shading normal, both pointing away
// from the surface (wo towards the viewer, wi towards the light), as in
// pbrt-v4 and Mitsuba 3. Also reflection, refraction and Fresnel's terms.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace kappa::bsdf {

inline float cos_theta(const Vec3f& w) { return w.z; }
inline float abs_cos_theta(const Vec3f& w) { return std::abs(w.z); }
inline float cos2_theta(const Vec3f& w) { return w.z * w.z; }
inline float sin2_theta(const Vec3f& w) { return std::max(0.0f, 1.0f - cos2_theta(w)); }
inline float tan2_theta(const Vec3f& w) { return sin2_theta(w) / cos2_theta(w); }
inline bool same_hemisphere(const Vec3f& a, const Vec3f& b) { return a.z * b.z > 0.0f; }

/// The mirror direction of wo about n (both unit, same side or not).
inline Vec3f reflect(const Vec3f& wo, const Vec3f& n) { return -wo + n * (2.0f * dot(wo, n)); }

/// Refracts wo through a surface of normal n (on wo's side or not) with
/// relative index eta = n_transmitted / n_incident seen from the +n side.
/// Returns false on total internal reflection; etap receives the index
/// ratio actually crossed (eta, or 1/eta from the -n side).
inline bool refract(const Vec3f& wo, Vec3f n, float eta, float& etap, Vec3f& wt) {
  float cos_i = dot(n, wo);
  if (cos_i < 0.0f) {  // inside: the ratio and the normal flip
    eta = 1.0f / eta;
    cos_i = -cos_i;
    n = -n;
  }
  const float sin2_i = std::max(0.0f, 1.0f - cos_i * cos_i);
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  wt = -wo / eta + n * (cos_i / eta - cos_t);
  etap = eta;
  return true;
}

/// Fresnel reflectance of a dielectric interface, unpolarised, exact
/// (pbrt-v4's FrDielectric): cos_i the cosine on the incident side, negative
/// from inside, eta = n_inside / n_outside. 1 past the critical angle.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  if (cos_i < 0.0f) {
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

/// Schlick's approximation with a colour at normal incidence (glTF 2.0's
/// conductor Fresnel, F0 = the base colour).
inline Vec3f fresnel_schlick(const Vec3f& f0, float cos_i) {
  const float m = std::clamp(1.0f - std::abs(cos_i), 0.0f, 1.0f);
  const float m5 = (m * m) * (m * m) * m;
  return f0 + (Vec3f{1, 1, 1} - f0) * m5;
}

}  // namespace kappa::bsdf
