// The Lambertian lobe: f = R / pi on wo's side, cosine-weighted sampling.
// The all-Lambertian frame keeps its own code (path_tracer.h); this lobe is
// the diffuse base of the layered model (principled.h).
#pragma once

#include <numbers>
#include <optional>

#include "renderer/bsdf/lobe_sample.h"
#include "renderer/bsdf/local_frame.h"
#include "core/warps.h"

namespace kappa::bsdf {

struct Lambertian {
  Vec3f R;  ///< reflectance in [0, 1]

  Vec3f eval(const Vec3f& wo, const Vec3f& wi) const {
    return same_hemisphere(wo, wi) ? R * std::numbers::inv_pi_v<float> : Vec3f{0, 0, 0};
  }
  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0.0f;
  }
  std::optional<LobeSample> sample(const Vec3f& wo, float u1, float u2) const {
    Vec3f wi = sample_cosine_hemisphere(u1, u2);
    if (wo.z < 0.0f) wi.z = -wi.z;
    const float p = cosine_hemisphere_pdf(abs_cos_theta(wi));
    if (!(p > 0.0f)) return std::nullopt;
    return LobeSample{eval(wo, wi), wi, p, 1.0f, Lobe::diffuse, false};
  }
};

}  // namespace kappa::bsdf
