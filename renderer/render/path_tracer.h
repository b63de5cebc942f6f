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
#include "renderer/render/frame.h"
#include "renderer/render/interaction.h"
#include "renderer/render/lights.h"
#include "renderer/render/path_variant.h"
#include "renderer/render/samplers.h"
#include "renderer/render/shading_point.h"
#include "renderer/render/sampling.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// What a camera sample records besides radiance.
struct FirstHit {
  Vec3f albedo{0, 0, 0};
  Vec3f normal{0, 0, 0};
  float depth = INFINITY;
};

class PathTracer {
 public:
  PathTracer(const Scene& scene, const RenderSettings& settings)
      : m_scene(scene), m_lights(scene), m_settings(settings) {}

  /// What the scene has to light it, for choose_path_variant.
  SceneLighting lighting() const {
    return {m_lights.triangle_count() > 0, !(m_scene.environment == Vec3f{0, 0, 0}), m_lights.pmf_environment() > 0.0f};
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

    for (int depth = 0;; ++depth) {
      const std::optional<Hit> hit = q.closest(ray, depth);
      if (!hit) {
        if constexpr (V.environment) {
          if (depth == 0 || !kLightSamples) {
            L += beta * m_scene.environment;
          } else if constexpr (kMis) {
            const float light_pdf =
                m_lights.pmf_environment() * cosine_hemisphere_pdf(dot(prev_normal, ray.d));
            L += beta * m_scene.environment * power_heuristic(prev_bsdf_pdf, light_pdf);
          } else if (m_lights.pmf_environment() == 0.0f) {
            L += beta * m_scene.environment;  // nee: an environment light sampling cannot pick
          }
        }
        break;
      }
      // Shading reads the shading point, never the accelerator's hit. The
      // Lambertian BSDF uses the geometric normal: the shading normal and
      // UVs are there for the materials that read them.
      const ShadingPoint shading = shading_point(m_scene, *hit);
      const Material& mat = *shading.material;
      const SurfacePoint& sp = shading.geometry;
      const Vec3f wo = -ray.d;
      const float cos_o = dot(sp.n, wo);
      const Vec3f n = cos_o >= 0.0f ? sp.n : -sp.n;  // reflect on the side the ray came from

      if constexpr (V.aovs) {
        if (depth == 0) first = FirstHit{mat.albedo, n, hit->t};
      }

      // Emission: one-sided, towards the geometric normal.
      if (mat.emissive() && cos_o > 0.0f) {
        if (depth == 0 || !V.triangle_lights) {
          // Seen directly, or no emitter is a light: BSDF sampling alone
          // finds it and carries its whole weight.
          L += beta * mat.emission;
        } else {
          // An emitter too dim to be a light (pmf 0) is reached only by BSDF
          // sampling, which then carries its whole weight.
          const float pmf = m_lights.pmf_of_triangle(hit->triangle);
          if constexpr (kMis) {
            // hit->t is the distance to the emitter only for a unit direction.
            KAPPA_DCHECK_LT(std::abs(dot(ray.d, ray.d) - 1.0f), 1e-5f);
            const float light_pdf =
                pmf > 0.0f ? pmf * (hit->t * hit->t) / (cos_o * m_lights.area_of_triangle(hit->triangle)) : 0.0f;
            L += beta * mat.emission * power_heuristic(prev_bsdf_pdf, light_pdf);
          } else if (pmf == 0.0f) {
            L += beta * mat.emission;  // nee: a light only BSDF sampling finds
          }
        }
      }
      if (depth >= m_settings.max_depth) break;
      if (mat.albedo == Vec3f{0, 0, 0}) break;  // black: nothing more to gather

      const Vec3f f = mat.albedo * std::numbers::inv_pi_v<float>;  // Lambertian BSDF
      if constexpr (kLightSamples) {
        // The general variant (both kinds on) keeps the run-time test for a
        // scene without lights; a specialised one knows it has some.
        if (!(V.triangle_lights && V.environment) || !m_lights.empty())
          L += beta * direct_light<V>(sp, n, f, sampler, depth, q);
      }

      // Continue the path by sampling the BSDF (cosine-weighted hemisphere).
      const auto [v1, v2] = sampler.get2D(path_dimensions::bsdf(depth));
      const Vec3f local = sample_cosine_hemisphere(v1, v2);
      const float pdf = cosine_hemisphere_pdf(local.z);
      if (!(pdf > 0.0f)) break;
      const Vec3f wi = Frame(n).to_world(local);
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
  /// One light sample, weighted against BSDF sampling by MIS (or alone, nee).
  template <PathVariant V, class Sampler, class Queries>
  Vec3f direct_light(const SurfacePoint& sp, const Vec3f& n, const Vec3f& f, Sampler& sampler, int depth,
                     Queries& q) const {
    constexpr bool kMis = V.strategy == LightSampling::mis;
    // The light choice's number is drawn even when there is one kind of
    // light, so that every variant reads the same numbers (an independent
    // sampler's stream is in order) and renders the general one's image.
    const double choice = sampler.get1D_double(path_dimensions::light_choice(depth));
    const auto [u1, u2] = sampler.get2D(path_dimensions::light_point(depth));
    std::size_t light = m_lights.environment_index();
    if constexpr (V.triangle_lights) light = m_lights.choose(choice);
    else (void)choice;
    if constexpr (V.environment) {
      if (light == m_lights.environment_index()) {
        // Cosine-weighted about the oriented normal: directions below the
        // surface would contribute nothing.
        const Vec3f local = sample_cosine_hemisphere(u1, u2);
        const float dir_pdf = cosine_hemisphere_pdf(local.z);
        if (!(dir_pdf > 0.0f)) return {};
        const Vec3f wi = Frame(n).to_world(local);
        const float light_pdf = m_lights.pmf_environment() * dir_pdf;
        if (!(light_pdf > 0.0f)) return {};
        if (q.shadow(Ray{offset_ray_origin(sp, wi), wi})) return {};
        const float weight = kMis ? power_heuristic(light_pdf, dir_pdf) : 1.0f;
        return f * m_scene.environment * (local.z * weight / light_pdf);
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
      if (!(dist2 > 0.0f)) return {};
      const Vec3f wi = to_light / std::sqrt(dist2);
      const float cos_s = dot(n, wi);
      const float cos_l = -dot(lp.n, wi);
      if (cos_s <= 0.0f || cos_l <= 0.0f) return {};
      const float light_pdf = m_lights.pmf(light) * dist2 / (cos_l * m_lights.area(light));
      if (!(light_pdf > 0.0f) || !std::isfinite(light_pdf)) return {};

      const Vec3f from = offset_ray_origin(sp, wi);
      const Vec3f to = offset_ray_origin(lp, -wi);
      const Vec3f d = to - from;
      const float len = length(d);
      if (!(len > 0.0f)) return {};
      if (q.shadow(Ray{from, d / len, 0.0f, len * (1.0f - kShadowEpsilon)})) return {};
      const Vec3f Le = m_scene.materials[m_scene.material_of[id]].emission;
      const float weight = kMis ? power_heuristic(light_pdf, cosine_hemisphere_pdf(cos_s)) : 1.0f;
      return f * Le * (cos_s * weight / light_pdf);
    }
    return {};
  }

  const Scene& m_scene;
  Lights m_lights;
  const RenderSettings& m_settings;
};

}  // namespace kappa
