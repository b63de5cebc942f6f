// The one material model, glTF 2.0's metallic-roughness BSDF (its
// specification, Appendix B, with KHR_materials_transmission and
// KHR_materials_ior), in the local shading frame:
//
//   material   = mix(dielectric, metal, metallic)
//   metal      = GGX * Schlick(F0 = base)                        (conductor.h)
//   dielectric = mix(opaque, glass, transmission)
//   opaque     = s F(wo.h) * GGX + (1 - s F(wo.h)) * base / pi   (fresnel_mix)
//   glass      = rough dielectric, refraction tinted             (dielectric.h)
//
// with F the exact dielectric Fresnel of the IOR (glTF writes Schlick's fit
// of it), s = 2 * specular (specular 0.5, the glTF and Blender default, is
// the IOR's own reflectance; 0 a purely diffuse surface), alpha = roughness^2.
// MTL and glTF land on these parameters (renderer/scene/material.h).
//
// Sampling picks one lobe (diffuse, the GGX reflection metal and opaque
// share, or the glass) with probabilities estimated from wo, then weighs the
// direction by the sum of every non-delta lobe's f and pdf (one-sample MIS
// with the balance heuristic across lobes). Delta lobes (alpha below
// kSmoothAlpha) are returned as delta samples, never by eval or pdf.
#pragma once

#include <algorithm>
#include <optional>

#include "renderer/bsdf/conductor.h"
#include "renderer/bsdf/dielectric.h"
#include "renderer/bsdf/lambertian.h"

namespace kappa::bsdf {

struct PrincipledParams {
  Vec3f base{0.5f, 0.5f, 0.5f};
  float roughness = 1;  ///< perceptual, alpha = roughness^2
  float metallic = 0;
  float specular = 0.5f;  ///< the opaque dielectric's Fresnel is scaled by 2 * specular
  float ior = 1.5f;
  float transmission = 0;
  Vec3f transmission_tint{1, 1, 1};
};

class Principled {
 public:
  explicit Principled(const PrincipledParams& p)
      : m_ggx(std::max(p.roughness * p.roughness, 0.0f)),
        m_base(p.base),
        m_metallic(p.metallic),
        m_spec_scale(2.0f * p.specular),
        m_ior(p.ior),
        m_transmission(p.transmission),
        m_glass{m_ggx, p.ior, p.transmission_tint} {}

  bool smooth() const { return m_ggx.smooth(); }
  /// Every lobe is a delta lobe: light sampling can add nothing.
  bool delta_only() const { return smooth() && (1.0f - m_metallic) * (1.0f - m_transmission) * max_component(m_base) <= 0.0f; }

  /// f(wo, wi) of the non-delta lobes.
  Vec3f eval(const Vec3f& wo, const Vec3f& wi) const {
    Vec3f f{0, 0, 0};
    const float w_opaque = (1.0f - m_metallic) * (1.0f - m_transmission);
    if (wo.z > 0.0f && wi.z > 0.0f) {
      const Vec3f wm = normalize(wo + wi);
      const float sF = opaque_fresnel(dot(wo, wm));
      if (w_opaque > 0.0f) f += m_base * (w_opaque * (1.0f - sF) * std::numbers::inv_pi_v<float>);
      if (!smooth()) {
        const float DG = m_ggx.D(wm) * m_ggx.G(wo, wi) / (4.0f * wo.z * wi.z);
        f += Vec3f{1, 1, 1} * (w_opaque * sF * DG);
        if (m_metallic > 0.0f) f += fresnel_schlick(m_base, dot(wo, wm)) * (m_metallic * DG);
      }
    }
    const float w_glass = (1.0f - m_metallic) * m_transmission;
    if (w_glass > 0.0f) f += m_glass.eval(wo, wi) * w_glass;
    return f;
  }

  /// The density of sample()'s non-delta directions.
  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    const Choice c = choice(wo);
    float p = 0;
    if (c.diffuse > 0.0f) p += c.diffuse * Lambertian{m_base}.pdf(wo, wi);
    if (c.glossy > 0.0f) p += c.glossy * reflection().pdf(wo, wi);
    if (c.glass > 0.0f) p += c.glass * m_glass.pdf(wo, wi);
    return p;
  }

  /// uc chooses the lobe (and, inside the glass, reflection or refraction);
  /// (u1, u2) the direction.
  std::optional<LobeSample> sample(const Vec3f& wo, float uc, float u1, float u2) const {
    if (wo.z == 0.0f) return std::nullopt;
    const Choice c = choice(wo);
    std::optional<LobeSample> s;
    if (uc < c.diffuse) {
      s = Lambertian{m_base}.sample(wo, u1, u2);
    } else if (uc < c.diffuse + c.glossy) {
      s = reflection().sample(wo, u1, u2);
      if (s && s->delta) {
        // The mirror: the metal's Schlick and the opaque layer's Fresnel
        // together, chosen with probability c.glossy.
        const float cos_o = abs_cos_theta(wo);
        const Vec3f F = fresnel_schlick(m_base, cos_o) * m_metallic +
                        Vec3f{1, 1, 1} * ((1.0f - m_metallic) * (1.0f - m_transmission) * opaque_fresnel(cos_o));
        s->f = F / abs_cos_theta(s->wi);
        s->pdf = c.glossy;
        return s;
      }
    } else if (c.glass > 0.0f) {
      const float uc_glass = std::min((uc - c.diffuse - c.glossy) / c.glass, 0x1.fffffep-1f);
      s = m_glass.sample(wo, uc_glass, u1, u2);
      if (s && s->delta) {
        s->f *= (1.0f - m_metallic) * m_transmission;
        s->pdf *= c.glass;
        return s;
      }
    }
    if (!s) return std::nullopt;
    // A non-delta direction: every non-delta lobe's f and the mixture's pdf.
    s->f = eval(wo, s->wi);
    s->pdf = pdf(wo, s->wi);
    if (!(s->pdf > 0.0f)) return std::nullopt;
    return s;
  }

  /// Probabilities of the three lobes for wo (summing to 1, or all 0).
  struct Choice {
    float diffuse = 0, glossy = 0, glass = 0;
  };
  Choice choice(const Vec3f& wo) const {
    const float w_opaque = (1.0f - m_metallic) * (1.0f - m_transmission);
    const float cos_o = abs_cos_theta(wo);
    Choice c;
    if (wo.z > 0.0f) {
      const float sF = opaque_fresnel(cos_o);
      if (w_opaque > 0.0f && max_component(m_base) > 0.0f) c.diffuse = w_opaque * std::max(1.0f - sF, 0.05f) * std::max(luminance(m_base), 0.05f);
      if (w_opaque * m_spec_scale > 0.0f) c.glossy += w_opaque * std::max(sF, 0.05f);
      if (m_metallic > 0.0f) c.glossy += m_metallic * std::max(luminance(fresnel_schlick(m_base, cos_o)), 0.05f);
    }
    if (m_transmission > 0.0f && m_metallic < 1.0f) c.glass = (1.0f - m_metallic) * m_transmission;
    const float sum = c.diffuse + c.glossy + c.glass;
    if (!(sum > 0.0f)) return {};
    return {c.diffuse / sum, c.glossy / sum, c.glass / sum};
  }

 private:
  /// The opaque layer's Fresnel, s F, at most 1.
  float opaque_fresnel(float cos_o) const {
    return m_spec_scale > 0.0f ? std::min(1.0f, m_spec_scale * fresnel_dielectric(cos_o, m_ior)) : 0.0f;
  }
  /// The GGX reflection the metal and the opaque layer share (its F is
  /// applied in eval; here only its sampling and pdf are used).
  Conductor reflection() const { return Conductor{m_ggx, Vec3f{1, 1, 1}}; }

  Ggx m_ggx;
  Vec3f m_base;
  float m_metallic, m_spec_scale, m_ior, m_transmission;
  Dielectric m_glass;
};

}  // namespace kappa::bsdf
