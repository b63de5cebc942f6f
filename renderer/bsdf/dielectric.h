// A dielectric interface that reflects and refracts: rough (Walter, Marschner,
// Li & Torrance 2007, "Microfacet Models for Refraction through Rough
// Surfaces", with GGX, Smith height-correlated masking and visible-normal
// sampling) or, below kSmoothAlpha, smooth glass (two delta lobes). Exact
// dielectric Fresnel; the refracted radiance scaled by 1/eta'^2 (radiance
// is transported, not importance: Veach 1997, sec. 5.2). The form is
// pbrt-v4's DielectricBxDF. eta = n_inside / n_outside, the outside on +z.
#pragma once

#include <cmath>
#include <optional>

#include "renderer/bsdf/ggx.h"
#include "renderer/bsdf/lobe_sample.h"

namespace kappa::bsdf {

struct Dielectric {
  Ggx ggx;
  float eta = 1.5f;
  Vec3f tint{1, 1, 1};  ///< multiplies refracted light (MTL Tf, glTF base colour)

  Vec3f eval(const Vec3f& wo, const Vec3f& wi) const {
    if (eta == 1.0f || ggx.smooth()) return {0, 0, 0};
    float etap = 1.0f;
    Vec3f wm;
    if (!half_vector(wo, wi, etap, wm)) return {0, 0, 0};
    const float F = fresnel_dielectric(dot(wo, wm), eta);
    const float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
    if (cos_o * cos_i > 0.0f) {
      const float f = ggx.D(wm) * ggx.G(wo, wi) * F / std::abs(4.0f * cos_i * cos_o);
      return {f, f, f};
    }
    const float denom = sq(dot(wi, wm) + dot(wo, wm) / etap) * cos_i * cos_o;
    const float ft = ggx.D(wm) * (1.0f - F) * ggx.G(wo, wi) * std::abs(dot(wi, wm) * dot(wo, wm) / denom) / sq(etap);
    return tint * ft;
  }

  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    if (eta == 1.0f || ggx.smooth()) return 0.0f;
    float etap = 1.0f;
    Vec3f wm;
    if (!half_vector(wo, wi, etap, wm)) return 0.0f;
    const float R = fresnel_dielectric(dot(wo, wm), eta), T = 1.0f - R;
    if (cos_theta(wo) * cos_theta(wi) > 0.0f)
      return ggx.D_visible(wo, wm) / (4.0f * std::abs(dot(wo, wm))) * R;
    const float denom = sq(dot(wi, wm) + dot(wo, wm) / etap);
    return ggx.D_visible(wo, wm) * std::abs(dot(wi, wm)) / denom * T;
  }

  /// uc in [0, 1) chooses reflection or refraction; (u1, u2) the normal.
  std::optional<LobeSample> sample(const Vec3f& wo, float uc, float u1, float u2) const {
    if (wo.z == 0.0f) return std::nullopt;
    if (eta == 1.0f || ggx.smooth()) return sample_smooth(wo, uc);
    // A normal visible from wo (on +z whichever side wo is: the Fresnel
    // term and refract() read the side from dot(wo, wm)).
    const Vec3f wm = ggx.sample_visible(wo, u1, u2);
    const float R = fresnel_dielectric(dot(wo, wm), eta);
    if (uc < R) {
      const Vec3f wi = reflect(wo, wm);
      if (!same_hemisphere(wo, wi)) return std::nullopt;
      const float p = pdf(wo, wi);
      if (!(p > 0.0f)) return std::nullopt;
      return LobeSample{eval(wo, wi), wi, p, 1.0f, Lobe::glossy, false};
    }
    float etap = 1.0f;
    Vec3f wi;
    if (!refract(wo, wm, eta, etap, wi) || same_hemisphere(wo, wi) || wi.z == 0.0f) return std::nullopt;
    const float p = pdf(wo, wi);
    if (!(p > 0.0f)) return std::nullopt;
    return LobeSample{eval(wo, wi), wi, p, etap, Lobe::transmission, false};
  }

 private:
  static float sq(float x) { return x * x; }

  /// The generalised half vector of (wo, wi) facing +z, and the index ratio
  /// crossed; false where no microfacet joins them (back-facing).
  bool half_vector(const Vec3f& wo, const Vec3f& wi, float& etap, Vec3f& wm) const {
    const float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
    if (cos_i == 0.0f || cos_o == 0.0f) return false;
    const bool reflection = cos_i * cos_o > 0.0f;
    etap = reflection ? 1.0f : (cos_o > 0.0f ? eta : 1.0f / eta);
    wm = wi * etap + wo;
    if (dot(wm, wm) == 0.0f) return false;
    wm = normalize(wm);
    if (wm.z < 0.0f) wm = -wm;
    // Microfacets seen from behind by either direction join nothing.
    return !(dot(wm, wi) * cos_i < 0.0f || dot(wm, wo) * cos_o < 0.0f);
  }

  std::optional<LobeSample> sample_smooth(const Vec3f& wo, float uc) const {
    const float R = fresnel_dielectric(cos_theta(wo), eta), T = 1.0f - R;
    if (uc < R || T <= 0.0f) {
      const Vec3f wi{-wo.x, -wo.y, wo.z};
      const float f = R / abs_cos_theta(wi);
      return LobeSample{{f, f, f}, wi, R, 1.0f, Lobe::specular, true};
    }
    float etap = 1.0f;
    Vec3f wi;
    if (!refract(wo, Vec3f{0, 0, 1}, eta, etap, wi) || wi.z == 0.0f) return std::nullopt;
    const Vec3f ft = tint * (T / abs_cos_theta(wi) / sq(etap));
    return LobeSample{ft, wi, T, etap, Lobe::transmission, true};
  }
};

}  // namespace kappa::bsdf
