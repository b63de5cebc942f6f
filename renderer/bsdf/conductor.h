// Microfacet reflection off a conductor: GGX with Smith height-correlated
// masking, sampled by visible normals, with Schlick's Fresnel of F0 = the
// base colour (glTF 2.0's metal_brdf); below kSmoothAlpha a mirror (delta).
#pragma once

#include <optional>

#include "renderer/bsdf/ggx.h"
#include "renderer/bsdf/lobe_sample.h"

namespace kappa::bsdf {

struct Conductor {
  Ggx ggx;
  Vec3f f0;  ///< reflectance at normal incidence

  Vec3f eval(const Vec3f& wo, const Vec3f& wi) const {
    if (ggx.smooth() || !same_hemisphere(wo, wi)) return {0, 0, 0};
    const float cos_o = abs_cos_theta(wo), cos_i = abs_cos_theta(wi);
    if (cos_o == 0.0f || cos_i == 0.0f) return {0, 0, 0};
    Vec3f wm = wo + wi;
    if (dot(wm, wm) == 0.0f) return {0, 0, 0};
    wm = normalize(wm);
    const Vec3f F = fresnel_schlick(f0, dot(wo, wm));
    return F * (ggx.D(wm) * ggx.G(wo, wi) / (4.0f * cos_o * cos_i));
  }

  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    if (ggx.smooth() || !same_hemisphere(wo, wi)) return 0.0f;
    Vec3f wm = wo + wi;
    if (dot(wm, wm) == 0.0f) return 0.0f;
    wm = normalize(wm);
    if (wm.z < 0.0f) wm = -wm;
    return ggx.D_visible(wo, wm) / (4.0f * std::abs(dot(wo, wm)));
  }

  std::optional<LobeSample> sample(const Vec3f& wo, float u1, float u2) const {
    if (wo.z == 0.0f) return std::nullopt;
    if (ggx.smooth()) {
      const Vec3f wi{-wo.x, -wo.y, wo.z};
      return LobeSample{fresnel_schlick(f0, wo.z) / abs_cos_theta(wi), wi, 1.0f, 1.0f, Lobe::specular, true};
    }
    const Vec3f wi = reflect(wo, ggx.sample_visible(wo, u1, u2));
    if (!same_hemisphere(wo, wi)) return std::nullopt;
    const float p = pdf(wo, wi);
    if (!(p > 0.0f)) return std::nullopt;
    return LobeSample{eval(wo, wi), wi, p, 1.0f, Lobe::glossy, false};
  }
};

}  // namespace kappa::bsdf
