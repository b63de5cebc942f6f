// The BSDF at a shading point, in world space: the material's lobes
// (principled.h) in the frame of the shading normal, with the geometric
// normal keeping the final say on sides. A reflected direction below the
// geometric surface, or a refracted one that does not cross it, is black
// (pbrt-v4, Mitsuba 3): shading normals bend the lobes, never leak light
// through the surface. eval returns f * |cos| so that the integrator never
// reads which normal the cosine is taken about.
#pragma once

#include <optional>

#include "renderer/bsdf/principled.h"
#include "core/warps.h"
#include "renderer/scene/material.h"

namespace kappa::bsdf {

inline PrincipledParams principled_params(const Material& m) {
  return {m.albedo, m.roughness, m.metallic, m.specular, m.ior, m.transmission, m.transmission_tint};
}

struct WorldSample {
  Vec3f f_cos;  ///< f * |cos(wi, shading normal)|
  Vec3f wi;
  float pdf = 0;
  float etap = 1;
  Lobe lobe = Lobe::diffuse;
  bool delta = false;
};

class Bsdf {
 public:
  /// `ng` the unit geometric normal (the triangle's winding), `ns` the unit
  /// shading normal, `wo` towards the viewer.
  Bsdf(const Material& m, Vec3f ng, Vec3f ns, const Vec3f& wo) : Bsdf(principled_params(m), m.refracts(), ng, ns, wo) {}
  /// The lobes of `p` (a material's parameters, its texture maps looked up);
  /// `refracts` as Material::refracts says of the material.
  Bsdf(const PrincipledParams& p, bool refracts, Vec3f ng, Vec3f ns, const Vec3f& wo) : m_lobes(p) {
    // Vertex normals say which side is outside; without them ns == ng.
    if (dot(ns, ng) < 0.0f) ng = -ng;
    // An opaque surface is two-sided: it reflects on the side it is seen from.
    if (!refracts && dot(ng, wo) < 0.0f) {
      ng = -ng;
      ns = -ns;
    }
    // A shading normal that faces away from the viewer while the surface
    // faces it gives way to the geometric normal here.
    if (dot(ns, wo) * dot(ng, wo) <= 0.0f) ns = ng;
    m_ng = ng;
    m_frame = Frame(ns);
  }

  bool delta_only() const { return m_lobes.delta_only(); }

  Vec3f eval_cos(const Vec3f& wo, const Vec3f& wi) const {
    const Vec3f lo = to_local(wo), li = to_local(wi);
    if (!sides_agree(wo, wi, lo, li)) return {0, 0, 0};
    return m_lobes.eval(lo, li) * abs_cos_theta(li);
  }
  float pdf(const Vec3f& wo, const Vec3f& wi) const { return m_lobes.pdf(to_local(wo), to_local(wi)); }

  std::optional<WorldSample> sample(const Vec3f& wo, float uc, float u1, float u2) const {
    const Vec3f lo = to_local(wo);
    const std::optional<LobeSample> s = m_lobes.sample(lo, uc, u1, u2);
    if (!s) return std::nullopt;
    const Vec3f wi = m_frame.to_world(s->wi);
    if (!sides_agree(wo, wi, lo, s->wi)) return std::nullopt;
    return WorldSample{s->f * abs_cos_theta(s->wi), wi, s->pdf, s->etap, s->lobe, s->delta};
  }

 private:
  Vec3f to_local(const Vec3f& w) const { return m_frame.to_local(w); }
  /// Reflection (same side of the shading frame) must stay on one side of
  /// the geometric surface, transmission must cross it.
  bool sides_agree(const Vec3f& wo, const Vec3f& wi, const Vec3f& lo, const Vec3f& li) const {
    const float geometric = dot(m_ng, wo) * dot(m_ng, wi);
    return same_hemisphere(lo, li) ? geometric > 0.0f : geometric < 0.0f;
  }

  Principled m_lobes;
  Vec3f m_ng;
  Frame m_frame{Vec3f{0, 0, 1}};
};

}  // namespace kappa::bsdf
