// The path tracer's per-sample work: unidirectional path tracing with
// next-event estimation, MIS and Russian roulette, asking every visibility
// query through a Queries object (queries.h) chosen once per frame, compiled
// per PathVariant (path_variant.h) so that a frame does only what its scene
// and settings need.
#pragma once

#include <cmath>
#include <numbers>
#include <optional>

#include "core/check.h"
#include "renderer/bsdf/bsdf.h"
#include "renderer/render/frame.h"
#include "renderer/render/camera.h"
#include "renderer/render/environment_map.h"
#include "renderer/render/interaction.h"
#include "renderer/render/lights.h"
#include "renderer/render/occluder_cache.h"
#include "renderer/render/path_variant.h"
#include "renderer/render/samplers.h"
#include "renderer/render/shading_point.h"
#include "renderer/render/sampling.h"
#include "renderer/scene/scene.h"
#include "renderer/texture/cutout_filter.h"
#include "renderer/texture/texture_lookup.h"
#include "renderer/texture/uv_footprint.h"

namespace kappa {

/// What a camera sample records besides radiance.
struct FirstHit {
  Vec3f albedo{0, 0, 0};
  Vec3f normal{0, 0, 0};
  float depth = INFINITY;
};

class PathTracer {
 public:
  /// `camera`, if given, gives camera rays' texture footprints (uv_footprint.h).
  PathTracer(const Scene& scene, const RenderSettings& settings, const Camera* camera = nullptr)
      : m_scene(scene), m_lights(scene), m_settings(settings), m_camera(camera), m_cutouts(scene) {
    if (scene.environment_image) m_env.emplace(*scene.environment_image, scene.environment_rotation_deg);
  }

  /// What the scene has to light it, for choose_path_variant.
  SceneLighting lighting() const {
    return {m_lights.triangle_count() > 0, !(m_scene.environment == Vec3f{0, 0, 0}), m_lights.pmf_environment() > 0.0f,
            m_env.has_value(), m_lights.punctual_count() > 0};
  }
  /// What its surfaces need, for choose_path_variant.
  SceneSurfaces surfaces() const {
    SceneSurfaces s;
    for (const TriangleNormals& n : m_scene.normals) s.vertex_normals = s.vertex_normals || n.given();
    s.non_lambertian = m_scene.has_materials();
    s.cutouts = m_cutouts.any();
    return s;
  }

  /// Radiance arriving along `ray`, asking every visibility query through
  /// `q` (PlainQueries or CountingQueries, chosen once per frame), each
  /// decision reading its numbers from `sampler` at its dimension
  /// (samplers.h, path_dimensions). `first` receives the camera ray's hit
  /// when V.aovs.
  template <PathVariant V, class Sampler, class Queries>
  Vec3f radiance(Ray ray, Sampler& sampler, FirstHit& first, Queries& q) const {
    constexpr bool kMis = V.strategy == LightSampling::mis;
    constexpr bool kLightSamples = V.strategy != LightSampling::bsdf;
    Vec3f L{0, 0, 0};
    Vec3f beta{1, 1, 1};
    float prev_bsdf_pdf = 0;  // solid-angle pdf of the direction that led here
    Vec3f prev_normal;        // oriented normal at the previous vertex
    // The direction that led here came from a delta lobe (a mirror, glass):
    // light sampling could not have found what it reaches.
    bool prev_delta = false;
    float eta_scale = 1;  // the refractions' 1/eta^2 undone for Russian roulette (pbrt-v4)
    bsdf::Lobe lobe = bsdf::Lobe::diffuse;  // the lobe that sampled the current ray

    for (int depth = 0;; ++depth) {
      // A scene with materials counts its bounce rays by lobe too.
      std::optional<Hit> hit;
      if constexpr (V.extras) {
        hit = m_cutouts.any() ? q.closest_by_lobe(ray, depth, lobe, m_cutouts) : q.closest_by_lobe(ray, depth, lobe);
      } else if constexpr (V.surfaces == Surfaces::general) {
        hit = q.closest_by_lobe(ray, depth, lobe);
      } else {
        hit = q.closest(ray, depth);
      }
      if (!hit) {
        if constexpr (V.environment) {
          // An image (V.extras, when the scene has one) or the constant.
          const bool image = V.extras && m_env.has_value();
          const Vec3f Le = image ? m_env->Le(ray.d) : m_scene.environment;
          if (depth == 0 || !kLightSamples || prev_delta) {
            L += beta * Le;
          } else if constexpr (kMis) {
            const float dir_pdf = image ? m_env->pdf(ray.d) : cosine_hemisphere_pdf(dot(prev_normal, ray.d));
            const float light_pdf = m_lights.pmf_environment() * dir_pdf;
            L += beta * Le * power_heuristic(prev_bsdf_pdf, light_pdf);
          } else if (m_lights.pmf_environment() == 0.0f) {
            L += beta * Le;  // nee: an environment light sampling cannot pick
          } else if constexpr (V.surfaces == Surfaces::general) {
            // nee: light sampling draws the constant environment about the
            // oriented normal; what refraction reached below it only BSDF
            // sampling finds (an image's samples cover the whole sphere).
            if (!image && !(dot(prev_normal, ray.d) > 0.0f)) L += beta * Le;
          }
        }
        break;
      }
      // Shading reads the shading point, never the accelerator's hit. The
      // geometric normal decides sides and ray offsets; the shading normal
      // only bends the BSDF (Surfaces::lambertian_smooth and general).
      const ShadingPoint shading = shading_point(m_scene, *hit);
      const Material& mat = *shading.material;
      const SurfacePoint& sp = shading.geometry;
      const Vec3f wo = -ray.d;
      const float cos_o = dot(sp.n, wo);
      const Vec3f n = cos_o >= 0.0f ? sp.n : -sp.n;  // reflect on the side the ray came from

      if constexpr (V.aovs) {
        if (depth == 0) first = FirstHit{mat.albedo, n, hit->t};
      }

      // Emission: towards the geometric normal, or both ways (emits_both_sides).
      if (mat.emissive() && (cos_o > 0.0f || (cos_o < 0.0f && mat.emits_both_sides))) {
        Vec3f Le = mat.emission;
        if constexpr (V.surfaces == Surfaces::general) {
          if (mat.has_map(MapSlot::emission)) Le = emitted(m_scene, mat, shading.uv);
        }
        if (depth == 0 || !V.triangle_lights || prev_delta) {
          // Seen directly (or through delta lobes), or no emitter is a light:
          // BSDF sampling alone finds it and carries its whole weight.
          L += beta * Le;
        } else {
          // An emitter too dim to be a light (pmf 0) is reached only by BSDF
          // sampling, which then carries its whole weight.
          const float pmf = m_lights.pmf_of_triangle(hit->triangle);
          if constexpr (kMis) {
            // hit->t is the distance to the emitter only for a unit direction.
            KAPPA_DCHECK_LT(std::abs(dot(ray.d, ray.d) - 1.0f), 1e-5f);
            const float light_pdf =
                pmf > 0.0f ? pmf * (hit->t * hit->t) / (std::abs(cos_o) * m_lights.area_of_triangle(hit->triangle)) : 0.0f;
            L += beta * Le * power_heuristic(prev_bsdf_pdf, light_pdf);
          } else if (pmf == 0.0f) {
            L += beta * Le;  // nee: a light only BSDF sampling finds
          }
        }
      }
      if (depth >= m_settings.max_depth) break;
      if constexpr (V.surfaces == Surfaces::general) {
        bsdf::PrincipledParams params = bsdf::principled_params(mat);
        if (mat.textured()) {
          params = textured_params(*hit, shading, mat, depth, ray);
          if constexpr (V.aovs) {
            if (depth == 0) first.albedo = params.base;
          }
        }
        if (!scatter_general<V>(shading, params, wo, n, depth, sampler, q, L, beta, ray, prev_bsdf_pdf, prev_normal,
                                prev_delta, eta_scale, lobe))
          break;
        continue;
      }
      if (mat.albedo == Vec3f{0, 0, 0}) break;  // black: nothing more to gather

      // The Lambertian vertex: about the geometric normal, or about the
      // shading normal (turned to the viewer's side) where the mesh gives one.
      Vec3f ns = n;
      if constexpr (V.surfaces == Surfaces::lambertian_smooth) ns = shading_side(shading.shading_normal, n, wo);
      const Vec3f f = mat.albedo * std::numbers::inv_pi_v<float>;  // Lambertian BSDF
      if constexpr (kLightSamples) {
        // The general variant (both kinds on) keeps the run-time test for a
        // scene without lights; a specialised one knows it has some.
        if (!(V.triangle_lights && V.environment) || !m_lights.empty())
          L += beta * direct_light<V>(sp, n, ns, f, sampler, depth, q);
      }

      // Continue the path by sampling the BSDF (cosine-weighted hemisphere).
      const auto [v1, v2] = sampler.get2D(path_dimensions::bsdf(depth));
      const Vec3f local = sample_cosine_hemisphere(v1, v2);
      const float pdf = cosine_hemisphere_pdf(local.z);
      if (!(pdf > 0.0f)) break;
      const Vec3f wi = Frame(ns).to_world(local);
      if constexpr (V.surfaces == Surfaces::lambertian_smooth) {
        if (!(dot(wi, n) > 0.0f)) break;  // below the geometric surface: black
      }
      beta *= mat.albedo;  // f * cos / pdf
      prev_bsdf_pdf = pdf;
      prev_normal = n;
      ray = Ray{offset_ray_origin(sp, wi), wi};

      if (m_settings.rr_depth >= 0 && depth + 1 >= m_settings.rr_depth) {
        const float q = std::max(0.0f, 1.0f - max_component(beta));
        if (sampler.get1D(path_dimensions::roulette(depth)) < q) break;
        beta /= 1.0f - q;
      }
    }
    return L;
  }

 private:
  /// The material's parameters with its texture maps looked up at the hit:
  /// a camera ray's with the pixel's footprint (scaled as pbrt-v4 does by
  /// max(1/8, 1/sqrt(spp)): more samples filter less), others at a point.
  bsdf::PrincipledParams textured_params(const Hit& hit, const ShadingPoint& shading, const Material& mat, int depth,
                                         const Ray& ray) const {
    UvFootprint fp;
    if (depth == 0 && m_camera && hit.triangle < m_scene.uvs.size()) {
      Vec3f dpdx, dpdy;
      m_camera->footprint(shading.geometry.p, shading.geometry.n, ray.d, dpdx, dpdy);
      const float scale = std::max(0.125f, 1.0f / std::sqrt(float(std::max(m_settings.spp, 1))));
      fp = uv_footprint(m_scene.triangles[hit.triangle], m_scene.uvs[hit.triangle], dpdx * scale, dpdy * scale);
    }
    bsdf::PrincipledParams p = bsdf::principled_params(mat);
    apply_texture_maps(m_scene, mat, shading.uv, fp, p);
    return p;
  }

  /// A shadow ray's query toward the light keyed `light` (occluder_cache.h:
  /// its index in m_lights, and for the environment the ray's part of the
  /// sky), through the cut-outs where the scene has them.
  template <PathVariant V, class Queries>
  bool occluded(const Ray& r, LightKey light, Queries& q) const {
    if constexpr (V.extras) {
      if (m_cutouts.any()) return q.shadow(r, light, m_cutouts);
    }
    return q.shadow(r, light);
  }

  /// The shading normal on the side of the oriented geometric normal n (the
  /// viewer's side), or n itself where the shading normal faces away from the
  /// viewer (a silhouette of a smooth mesh: it would leave a black spot).
  static Vec3f shading_side(Vec3f ns, const Vec3f& n, const Vec3f& wo) {
    if (dot(ns, n) < 0.0f) ns = -ns;
    return dot(ns, wo) > 0.0f ? ns : n;
  }

  /// A light sample: its direction, the radiance it brings, the light
  /// sampling's pdf of the direction (solid angle) and its cosine about the
  /// oriented geometric normal. None when it brings nothing or is occluded.
  struct LightSample {
    Vec3f wi;
    Vec3f Le;
    float pdf = 0;
    float cos = 0;
    /// A punctual light: Le is its irradiance (normal to wi), pdf only the
    /// probability of choosing it, and no MIS weight applies (BSDF sampling
    /// cannot hit it).
    bool delta = false;
  };

  /// A punctual light's sample at sp (chosen with probability pmf): the
  /// irradiance it brings along wi, unless occluded. Point and spot lights
  /// fall off as 1/d^2, a spot's cone as glTF's KHR_lights_punctual
  /// specifies (its smooth attenuation, squared); a directional light's rays
  /// are parallel and unoccluded to infinity.
  template <PathVariant V, class Queries>
  std::optional<LightSample> sample_punctual(const SurfacePoint& sp, const Vec3f& n, bool two_sided,
                                             const PunctualLight& light, std::size_t index, float pmf,
                                             Queries& q) const {
    if (!(pmf > 0.0f)) return std::nullopt;
    if (light.type == PunctualLight::Type::directional) {
      const Vec3f wi = -light.direction;
      const float cos_s = dot(n, wi);
      if ((!two_sided && cos_s <= 0.0f) || cos_s == 0.0f) return std::nullopt;
      if (occluded<V>(Ray{offset_ray_origin(sp, wi), wi}, light_key(index), q)) return std::nullopt;
      return LightSample{wi, light.intensity, pmf, cos_s, true};
    }
    const Vec3f to_light = light.position - sp.p;
    const float dist2 = dot(to_light, to_light);
    if (!(dist2 > 0.0f)) return std::nullopt;
    const Vec3f wi = to_light / std::sqrt(dist2);
    const float cos_s = dot(n, wi);
    if ((!two_sided && cos_s <= 0.0f) || cos_s == 0.0f) return std::nullopt;
    float falloff = 1.0f;
    if (light.type == PunctualLight::Type::spot) {
      const float scale = 1.0f / std::max(0.001f, light.cos_inner - light.cos_outer);
      const float t = std::clamp((dot(-wi, light.direction) - light.cos_outer) * scale, 0.0f, 1.0f);
      falloff = t * t;
      if (!(falloff > 0.0f)) return std::nullopt;
    }
    const Vec3f from = offset_ray_origin(sp, wi);
    const Vec3f d = light.position - from;
    const float len = length(d);
    if (!(len > 0.0f)) return std::nullopt;
    if (occluded<V>(Ray{from, d / len, 0.0f, len * (1.0f - kShadowEpsilon)}, light_key(index), q)) return std::nullopt;
    return LightSample{wi, light.intensity * (falloff / dist2), pmf, cos_s, true};
  }

  /// One light sample at a vertex with oriented geometric normal n, for a
  /// surface that may transmit (`two_sided`: a light behind n counts).
  template <PathVariant V, class Sampler, class Queries>
  std::optional<LightSample> sample_light(const SurfacePoint& sp, const Vec3f& n, bool two_sided, Sampler& sampler,
                                          int depth, Queries& q) const {
    // The light choice's number is drawn even when there is one kind of
    // light, so that every variant reads the same numbers (an independent
    // sampler's stream is in order) and renders the general one's image.
    const double choice = sampler.get1D_double(path_dimensions::light_choice(depth));
    const auto [u1, u2] = sampler.get2D(path_dimensions::light_point(depth));
    std::size_t light = m_lights.environment_index();
    if constexpr (V.triangle_lights) light = m_lights.choose(choice);
    else (void)choice;
    if constexpr (V.extras) {
      if (const std::ptrdiff_t k = m_lights.punctual(light); k >= 0)
        return sample_punctual<V>(sp, n, two_sided, m_scene.punctual_lights[std::size_t(k)], light,
                                  m_lights.pmf(light), q);
    }
    if constexpr (V.environment) {
      if (light == m_lights.environment_index()) {
        if constexpr (V.extras) {
          if (m_env) {
            // An image: drawn by its luminance over the whole sphere.
            const std::optional<EnvironmentMap::Sample> es = m_env->sample(u1, u2);
            if (!es) return std::nullopt;
            const float cos_s = dot(n, es->wi);
            if ((!two_sided && cos_s <= 0.0f) || cos_s == 0.0f) return std::nullopt;
            const float light_pdf = m_lights.pmf_environment() * es->pdf;
            if (!(light_pdf > 0.0f)) return std::nullopt;
            if (occluded<V>(Ray{offset_ray_origin(sp, es->wi), es->wi}, light_key(light, es->wi), q)) return std::nullopt;
            return LightSample{es->wi, es->Le, light_pdf, cos_s};
          }
        }
        // Cosine-weighted about the oriented normal, as for the Lambertian
        // vertex: the same light pdf that the escaped ray's MIS weight reads.
        const Vec3f local = sample_cosine_hemisphere(u1, u2);
        const float dir_pdf = cosine_hemisphere_pdf(local.z);
        if (!(dir_pdf > 0.0f)) return std::nullopt;
        const Vec3f wi = Frame(n).to_world(local);
        const float light_pdf = m_lights.pmf_environment() * dir_pdf;
        if (!(light_pdf > 0.0f)) return std::nullopt;
        if (occluded<V>(Ray{offset_ray_origin(sp, wi), wi}, light_key(light, wi), q)) return std::nullopt;
        return LightSample{wi, m_scene.environment, light_pdf, local.z};
      }
    }
    if constexpr (V.triangle_lights) {
      const TriangleId id = m_lights.triangle(light);
      const Triangle& tri = m_scene.triangles[id];
      float b0, b1, b2;
      sample_triangle(u1, u2, b0, b1, b2);
      const SurfacePoint lp = surface_point(tri, b0, b1, b2);
      const Vec3f to_light = lp.p - sp.p;
      const float dist2 = dot(to_light, to_light);
      if (!(dist2 > 0.0f)) return std::nullopt;
      const Vec3f wi = to_light / std::sqrt(dist2);
      const float cos_s = dot(n, wi);
      float cos_l = -dot(lp.n, wi);
      // Its back: lit only by an emitter that emits both ways.
      if (cos_l < 0.0f && m_scene.materials[m_scene.material_of[id]].emits_both_sides) cos_l = -cos_l;
      if ((!two_sided && cos_s <= 0.0f) || cos_s == 0.0f || cos_l <= 0.0f) return std::nullopt;
      const float light_pdf = m_lights.pmf(light) * dist2 / (cos_l * m_lights.area(light));
      if (!(light_pdf > 0.0f) || !std::isfinite(light_pdf)) return std::nullopt;

      const Vec3f from = offset_ray_origin(sp, wi);
      const Vec3f to = offset_ray_origin(lp, -wi);
      const Vec3f d = to - from;
      const float len = length(d);
      if (!(len > 0.0f)) return std::nullopt;
      if (occluded<V>(Ray{from, d / len, 0.0f, len * (1.0f - kShadowEpsilon)}, light_key(light), q)) return std::nullopt;
      const Material& emitter = m_scene.materials[m_scene.material_of[id]];
      Vec3f Le = emitter.emission;
      if constexpr (V.surfaces == Surfaces::general) {
        if (emitter.has_map(MapSlot::emission)) {
          const TriangleUVs uvs = id < m_scene.uvs.size() ? m_scene.uvs[id] : TriangleUVs{};
          Le = emitted(m_scene, emitter, uvs.uv[0] * b0 + uvs.uv[1] * b1 + uvs.uv[2] * b2);
        }
      }
      return LightSample{wi, Le, light_pdf, cos_s};
    }
    return std::nullopt;
  }

  /// The general vertex (V.surfaces == general): light sampling through the
  /// BSDF's non-delta lobes, then the BSDF's own sample continues the path.
  /// False when the path ends here.
  template <PathVariant V, class Sampler, class Queries>
  bool scatter_general(const ShadingPoint& shading, const bsdf::PrincipledParams& params, const Vec3f& wo,
                       const Vec3f& n, int depth, Sampler& sampler,
                       Queries& q, Vec3f& L, Vec3f& beta, Ray& ray, float& prev_bsdf_pdf, Vec3f& prev_normal,
                       bool& prev_delta, float& eta_scale, bsdf::Lobe& lobe) const {
    constexpr bool kMis = V.strategy == LightSampling::mis;
    constexpr bool kLightSamples = V.strategy != LightSampling::bsdf;
    const Material& mat = *shading.material;
    const SurfacePoint& sp = shading.geometry;
    const bsdf::Bsdf f(params, mat.refracts(), sp.n, shading.shading_normal, wo);
    if constexpr (kLightSamples) {
      // Delta lobes alone: no light sample can reach them (the numbers of
      // its dimensions are left unread).
      if (!f.delta_only() && !m_lights.empty()) {
        if (const auto ls = sample_light<V>(sp, n, mat.refracts(), sampler, depth, q)) {
          const Vec3f f_cos = f.eval_cos(wo, ls->wi);
          if (!(f_cos == Vec3f{0, 0, 0})) {
            const float weight = kMis && !ls->delta ? power_heuristic(ls->pdf, f.pdf(wo, ls->wi)) : 1.0f;
            L += beta * f_cos * ls->Le * (weight / ls->pdf);
          }
        }
      }
    }
    const float uc = sampler.get1D(path_dimensions::bsdf_lobe(depth));
    const auto [v1, v2] = sampler.get2D(path_dimensions::bsdf(depth));
    const std::optional<bsdf::WorldSample> s = f.sample(wo, uc, v1, v2);
    if (!s || !(s->pdf > 0.0f)) return false;
    const Vec3f weight = s->f_cos / s->pdf;
    if (weight == Vec3f{0, 0, 0} || !is_finite(weight)) return false;
    beta *= weight;
    prev_bsdf_pdf = s->pdf;
    prev_normal = n;
    prev_delta = s->delta;
    lobe = s->lobe;
    if (s->lobe == bsdf::Lobe::transmission) eta_scale *= s->etap * s->etap;
    ray = Ray{offset_ray_origin(sp, s->wi), s->wi};

    if (m_settings.rr_depth >= 0 && depth + 1 >= m_settings.rr_depth) {
      const float q_end = std::max(0.0f, 1.0f - max_component(beta * eta_scale));
      if (sampler.get1D(path_dimensions::roulette(depth)) < q_end) return false;
      beta /= 1.0f - q_end;
    }
    return true;
  }

  /// One light sample, weighted against BSDF sampling by MIS (or alone, nee),
  /// for the Lambertian vertex: the cosine about ns, the shading normal
  /// (n itself unless V.surfaces is lambertian_smooth).
  template <PathVariant V, class Sampler, class Queries>
  Vec3f direct_light(const SurfacePoint& sp, const Vec3f& n, const Vec3f& ns, const Vec3f& f, Sampler& sampler,
                     int depth, Queries& q) const {
    constexpr bool kMis = V.strategy == LightSampling::mis;
    const auto ls = sample_light<V>(sp, n, false, sampler, depth, q);
    if (!ls) return {};
    float cos_s = ls->cos;
    if constexpr (V.surfaces == Surfaces::lambertian_smooth) {
      cos_s = dot(ns, ls->wi);
      if (!(cos_s > 0.0f)) return {};
    } else {
      (void)ns;
    }
    const float weight = kMis ? power_heuristic(ls->pdf, cosine_hemisphere_pdf(cos_s)) : 1.0f;
    return f * ls->Le * (cos_s * weight / ls->pdf);
  }

  const Scene& m_scene;
  Lights m_lights;
  const RenderSettings& m_settings;
  const Camera* m_camera;
  CutoutFilter m_cutouts;
  std::optional<EnvironmentMap> m_env;
};

}  // namespace kappa
