#include "renderer/render/ray_sets.h"

#include <algorithm>
#include <cmath>
#include "core/check.h"
#include "core/input_error.h"
#include "renderer/render/camera.h"
#include "renderer/render/interaction.h"
#include "renderer/render/lights.h"
#include "renderer/render/sampling.h"
#include "renderer/render/shading_point.h"
#include "stats/synthetic_rays.h"

namespace kappa {
namespace {

/// A camera hit: where bounce and shadow rays start.
struct SurfaceSample {
  SurfacePoint sp;
  Vec3f n;  ///< normal facing the camera ray's origin
};

/// The pixel of stratum k of `strata` over a width x height film: a grid of
/// about sqrt(strata) columns by rows, each stratum the pixel at the centre
/// of its cell, so fewer rays than pixels still cover the whole film (the
/// pixel index k * pixels / strata, used before, put every ray in one column
/// whenever pixels / strata was a multiple of the width).
std::size_t stratum_pixel(std::size_t k, std::size_t strata, int width, int height) {
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  if (strata == pixels) return k;
  const double aspect = double(width) / double(height);
  const std::size_t columns =
      std::clamp<std::size_t>(std::size_t(std::ceil(std::sqrt(double(strata) * aspect))), 1, std::size_t(width));
  const std::size_t rows = (strata + columns - 1) / columns;
  const std::size_t x = std::size_t((double(k % columns) + 0.5) * double(width) / double(columns));
  const std::size_t y = std::size_t((double(k / columns) + 0.5) * double(height) / double(rows));
  return std::min(y, std::size_t(height) - 1) * std::size_t(width) + std::min(x, std::size_t(width) - 1);
}

Ray camera_ray(const Scene& scene, const Camera& camera, std::size_t i, std::size_t n, std::uint64_t seed) {
  const std::size_t pixels = std::size_t(scene.width) * std::size_t(scene.height);
  // Fewer rays than pixels: spread them evenly over the film; more: cycle.
  // Either way ray i + strata lands on the same pixel with a new sample.
  const std::size_t strata = std::min(n, pixels);
  const std::size_t pixel = stratum_pixel(i % strata, strata, scene.width, scene.height);
  Rng rng(seed, pixel, i / strata);
  const float x = float(pixel % std::size_t(scene.width)) + rng.uniform();
  const float y = float(pixel / std::size_t(scene.width)) + rng.uniform();
  return camera.generate_ray(x, y);
}

/// Camera hits, in order, until `n` are found or 4n camera rays were tried.
std::vector<SurfaceSample> camera_hits(const Scene& scene, const Accelerator& accel, std::size_t n,
                                       std::uint64_t seed) {
  const Camera camera(scene.camera, scene.width, scene.height);
  std::vector<SurfaceSample> hits;
  hits.reserve(n);
  for (std::size_t i = 0; i < 4 * n && hits.size() < n; ++i) {
    const Ray r = camera_ray(scene, camera, i, n, seed);
    const auto hit = accel.closest_hit(r);
    if (!hit) continue;
    const SurfacePoint sp = shading_point(scene, *hit).geometry;
    hits.push_back({sp, dot(sp.n, r.d) < 0.0f ? sp.n : -sp.n});
  }
  return hits;
}

Ray cosine_ray(const SurfaceSample& s, Rng& rng) {
  const Vec3f local = sample_cosine_hemisphere(rng.uniform(), rng.uniform());
  const Vec3f w = Frame(s.n).to_world(local);
  return Ray{offset_ray_origin(s.sp, w), w};
}

}  // namespace

const char* ray_class_name(RayClass c) {
  switch (c) {
    case RayClass::camera: return "camera";
    case RayClass::bounce: return "bounce";
    case RayClass::shadow: return "shadow";
    case RayClass::lines: return "lines";
  }
  KAPPA_UNREACHABLE();  // every enumerator is handled above
}

RayClass parse_ray_class(const std::string& name) {
  for (RayClass c : {RayClass::camera, RayClass::bounce, RayClass::shadow, RayClass::lines})
    if (name == ray_class_name(c)) return c;
  throw InputError("unknown ray class '" + name + "' (expected camera, bounce, shadow, lines)");
}

RaySet make_ray_set(RayClass kind, const Scene& scene, const Accelerator& reference, std::size_t n,
                    std::uint64_t seed) {
  RaySet set;
  set.kind = kind;
  set.rays.reserve(n);
  Rng rng(seed, 0x6265'6e63'68ull, std::uint64_t(kind));  // one stream per class ("bench")

  if (kind == RayClass::camera) {
    const Camera camera(scene.camera, scene.width, scene.height);
    for (std::size_t i = 0; i < n; ++i) set.rays.push_back(camera_ray(scene, camera, i, n, seed));
    set.note = "stratified over the " + std::to_string(scene.width) + "x" + std::to_string(scene.height) + " film";
  } else if (kind == RayClass::bounce || kind == RayClass::shadow) {
    const auto hits = camera_hits(scene, reference, n, seed);
    const Lights lights(scene);
    const bool emitters = !lights.empty() && lights.environment_index() > 0;
    set.occlusion = kind == RayClass::shadow;
    for (std::size_t i = 0; !hits.empty() && i < n; ++i) {
      const SurfaceSample& s = hits[i % hits.size()];
      if (kind == RayClass::bounce || !emitters) {
        Ray r = cosine_ray(s, rng);
        set.rays.push_back(r);
        continue;
      }
      // To a point on an emitter chosen by power (the environment excluded).
      std::size_t light = lights.choose(rng.uniform_double());
      while (light == lights.environment_index()) light = lights.choose(rng.uniform_double());
      const Triangle& tri = scene.triangles[lights.triangle(light)];
      float b0, b1, b2;
      sample_triangle(rng.uniform(), rng.uniform(), b0, b1, b2);
      const SurfacePoint lp = surface_point(tri, b0, b1, b2);
      const Vec3f w = normalize(lp.p - s.sp.p);
      const Vec3f from = offset_ray_origin(s.sp, w), to = offset_ray_origin(lp, -w);
      const float len = length(to - from);
      if (!(len > 0.0f)) continue;
      set.rays.push_back(Ray{from, (to - from) / len, 0.0f, len * (1.0f - kShadowEpsilon)});
    }
    set.note = hits.empty() ? "the camera sees nothing: no rays"
               : kind == RayClass::bounce ? "cosine-weighted from camera hits"
               : emitters ? "from camera hits to points on emitters"
                          : "no emitters: cosine-weighted from camera hits, infinite tmax";
  } else {
    const Bounds3f b = scene.bounds();
    set.rays = uniform_lines(Vec3d(b.lo), Vec3d(b.hi), n, seed);
    set.note = "isotropic uniform lines through the scene box";
  }
  return set;
}

}  // namespace kappa
