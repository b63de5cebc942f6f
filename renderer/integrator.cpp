#include "integrator.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

#include "accel/grid.h"
#include "camera.h"
#include "queries.h"
#include "interaction.h"
#include "lights.h"
#include "sampling.h"

namespace kappa {
namespace {

constexpr int kTileSize = 16;

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

  /// Radiance arriving along `ray`, asking every visibility query through
  /// `q` (PlainQueries or CountingQueries, chosen once per frame).
  template <class Queries>
  Vec3f radiance(Ray ray, Rng& rng, FirstHit& first, Queries& q) const {
    Vec3f L{0, 0, 0};
    Vec3f beta{1, 1, 1};
    float prev_bsdf_pdf = 0;  // solid-angle pdf of the direction that led here
    Vec3f prev_normal;        // oriented normal at the previous vertex

    for (int depth = 0;; ++depth) {
      const std::optional<Hit> hit = q.closest(ray, depth);
      if (!hit) {
        if (depth == 0) {
          L += beta * m_scene.environment;
        } else {
          const float light_pdf =
              m_lights.pmf_environment() * cosine_hemisphere_pdf(dot(prev_normal, ray.d));
          L += beta * m_scene.environment * power_heuristic(prev_bsdf_pdf, light_pdf);
        }
        break;
      }
      const Triangle& tri = m_scene.triangles[hit->triangle];
      const Material& mat = m_scene.materials[m_scene.material_of[hit->triangle]];
      const SurfacePoint sp = surface_point(tri, hit->b0, hit->b1, hit->b2);
      const Vec3f wo = -ray.d;
      const float cos_o = dot(sp.n, wo);
      const Vec3f n = cos_o >= 0.0f ? sp.n : -sp.n;  // reflect on the side the ray came from

      if (depth == 0) first = FirstHit{mat.albedo, n, hit->t};

      // Emission: one-sided, towards the geometric normal.
      if (mat.emissive() && cos_o > 0.0f) {
        if (depth == 0) {
          L += beta * mat.emission;
        } else {
          // An emitter too dim to be a light (pmf 0) is reached only by BSDF
          // sampling, which then carries its whole weight.
          const float pmf = m_lights.pmf_of_triangle(hit->triangle);
          const float light_pdf =
              pmf > 0.0f ? pmf * (hit->t * hit->t) / (cos_o * m_lights.area_of_triangle(hit->triangle)) : 0.0f;
          L += beta * mat.emission * power_heuristic(prev_bsdf_pdf, light_pdf);
        }
      }
      if (depth >= m_settings.max_depth) break;
      if (mat.albedo == Vec3f{0, 0, 0}) break;  // black: nothing more to gather

      const Vec3f f = mat.albedo * std::numbers::inv_pi_v<float>;  // Lambertian BSDF
      if (!m_lights.empty()) L += beta * direct_light(sp, n, f, rng, q);

      // Continue the path by sampling the BSDF (cosine-weighted hemisphere).
      const Vec3f local = sample_cosine_hemisphere(rng.uniform(), rng.uniform());
      const float pdf = cosine_hemisphere_pdf(local.z);
      if (!(pdf > 0.0f)) break;
      const Vec3f wi = Frame(n).to_world(local);
      beta *= mat.albedo;  // f * cos / pdf
      prev_bsdf_pdf = pdf;
      prev_normal = n;
      ray = Ray{offset_ray_origin(sp, wi), wi};

      if (m_settings.rr_depth >= 0 && depth + 1 >= m_settings.rr_depth) {
        const float q = std::max(0.0f, 1.0f - max_component(beta));
        if (rng.uniform() < q) break;
        beta /= 1.0f - q;
      }
    }
    return L;
  }

 private:
  /// One light sample with its MIS weight against BSDF sampling.
  template <class Queries>
  Vec3f direct_light(const SurfacePoint& sp, const Vec3f& n, const Vec3f& f, Rng& rng, Queries& q) const {
    const std::size_t light = m_lights.choose(rng.uniform_double());
    const float u1 = rng.uniform(), u2 = rng.uniform();
    if (light == m_lights.environment_index()) {
      // Cosine-weighted about the oriented normal: directions below the
      // surface would contribute nothing.
      const Vec3f local = sample_cosine_hemisphere(u1, u2);
      const float dir_pdf = cosine_hemisphere_pdf(local.z);
      if (!(dir_pdf > 0.0f)) return {};
      const Vec3f wi = Frame(n).to_world(local);
      const float light_pdf = m_lights.pmf_environment() * dir_pdf;
      if (q.shadow(Ray{offset_ray_origin(sp, wi), wi})) return {};
      const float weight = power_heuristic(light_pdf, dir_pdf);
      return f * m_scene.environment * (local.z * weight / light_pdf);
    }

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
    const float weight = power_heuristic(light_pdf, cosine_hemisphere_pdf(cos_s));
    return f * Le * (cos_s * weight / light_pdf);
  }

  const Scene& m_scene;
  Lights m_lights;
  const RenderSettings& m_settings;
};

bool finite(const Vec3f& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

namespace {

/// The tile loop, for one choice of queries. `make_queries` gives a thread
/// its Queries object for a tile.
template <class MakeQueries>
RenderResult render_tiles(const Scene& scene, const RenderSettings& settings, Film& film, const ProgressCallback& progress,
                          MakeQueries&& make_queries) {
  const Camera camera(scene.camera, film.width, film.height);
  const PathTracer tracer(scene, settings);
  const int tiles_x = (film.width + kTileSize - 1) / kTileSize;
  const int tiles_y = (film.height + kTileSize - 1) / kTileSize;
  const std::size_t tile_count = std::size_t(tiles_x) * std::size_t(tiles_y);

  struct Counters {
    std::uint64_t rays = 0, rejected = 0;
  };
  tbb::enumerable_thread_specific<Counters> counters;
  std::atomic<std::size_t> tiles_done{0};
  const double inv_spp = 1.0 / double(settings.spp);

  tbb::parallel_for(std::size_t(0), tile_count, [&](std::size_t tile) {
    Counters& local = counters.local();
    auto queries = make_queries();
    const int x0 = int(tile % std::size_t(tiles_x)) * kTileSize;
    const int y0 = int(tile / std::size_t(tiles_x)) * kTileSize;
    for (int y = y0; y < std::min(y0 + kTileSize, film.height); ++y) {
      for (int x = x0; x < std::min(x0 + kTileSize, film.width); ++x) {
        const std::size_t pixel = std::size_t(y) * std::size_t(film.width) + std::size_t(x);
        double sum[3] = {0, 0, 0}, albedo[3] = {0, 0, 0}, normal[3] = {0, 0, 0}, depth = 0;
        int hits = 0;
        const QueryWork before = film.cost_cells.empty() ? QueryWork{} : queries.work();
        for (int s = 0; s < settings.spp; ++s) {
          Rng rng(settings.seed, pixel, std::uint64_t(s));
          queries.begin_path(pixel, std::uint64_t(s));
          const float fx = rng.uniform(), fy = rng.uniform();
          FirstHit first;
          Vec3f L = tracer.radiance(camera.generate_ray(float(x) + fx, float(y) + fy), rng, first, queries);
          if (!finite(L)) {
            ++local.rejected;
            L = {0, 0, 0};
          }
          sum[0] += L.x, sum[1] += L.y, sum[2] += L.z;
          albedo[0] += first.albedo.x, albedo[1] += first.albedo.y, albedo[2] += first.albedo.z;
          normal[0] += first.normal.x, normal[1] += first.normal.y, normal[2] += first.normal.z;
          if (std::isfinite(first.depth)) {
            depth += first.depth;
            ++hits;
          }
        }
        for (int c = 0; c < 3; ++c) film.rgb[3 * pixel + std::size_t(c)] = float(sum[c] * inv_spp);
        if (!film.albedo.empty())
          for (int c = 0; c < 3; ++c) film.albedo[3 * pixel + std::size_t(c)] = float(albedo[c] * inv_spp);
        if (!film.normal.empty()) {
          const double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
          for (int c = 0; c < 3; ++c)
            film.normal[3 * pixel + std::size_t(c)] = len > 0 ? float(normal[c] / len) : 0.0f;
        }
        if (!film.depth.empty()) film.depth[pixel] = hits > 0 ? float(depth / hits) : INFINITY;
        if (!film.cost_cells.empty()) {
          const QueryWork after = queries.work();
          film.cost_cells[pixel] = float(after.cells - before.cells);
          film.cost_tests[pixel] = float(after.tests - before.tests);
        }
      }
    }
    local.rays += queries.rays;
    const std::size_t done = tiles_done.fetch_add(1, std::memory_order_relaxed) + 1;
    if (progress) progress(done, tile_count);
  });

  RenderResult result;
  counters.combine_each([&](const Counters& c) {
    result.rays += c.rays;
    result.rejected_samples += c.rejected;
  });
  return result;
}

#ifndef KAPPA_NO_STATS
/// The frame with statistics: the grid walked with per-class counters.
RenderResult render_counting(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress) {
  RenderResult result;
  // Per-cell arrays per class and per thread must fit beside the grid in
  // --grid-max-bytes, with what the report adds (64-bit visits folded per
  // class, and one 64-bit array for the classes together); otherwise only
  // per-class totals are kept.
  const std::uint64_t cells = grid.info().resolution.cells();
  const std::uint64_t threads =
      std::uint64_t(settings.threads > 0 ? settings.threads : tbb::this_task_arena::max_concurrency());
  const std::uint64_t need = per_cell_stats_bytes(cells, threads);
  const bool per_cell = grid.info().bytes + need <= settings.stats_max_bytes;
  const std::uint64_t every = settings.cell_sample > 0 ? settings.cell_sample : auto_cell_sample(cells);
  const CellSampling sampling{per_cell ? every : 1, settings.seed};
  tbb::enumerable_thread_specific<RenderCounters> per_thread(
      [&] { return RenderCounters(grid.info().resolution, per_cell); });
  result = render_tiles(scene, settings, film, progress,
                        [&] { return CountingQueries(grid, per_thread.local(), sampling); });
  // Merge into one thread's counters: no further copy of the arrays.
  std::shared_ptr<RenderCounters> merged;
  for (RenderCounters& c : per_thread) {
    if (!merged) merged = std::make_shared<RenderCounters>(std::move(c));
    else merged->merge(c);
  }
  if (!merged) merged = std::make_shared<RenderCounters>(grid.info().resolution, per_cell);
  result.counters = merged;
  result.cell_sample = sampling.every;
  if (!per_cell)
    result.stats_note = "per-cell statistics refused: " + std::to_string(need >> 20) +
                        " MiB of counters would exceed --grid-max-bytes; per-class totals only";
  return result;
}
#endif

}  // namespace

RenderResult render(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                    const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(settings.threads));

  RenderResult result;
#ifndef KAPPA_NO_STATS  // a build without statistics has no trace of them here
  if (const auto* grid = dynamic_cast<const UniformGrid*>(&accel); settings.stats && grid)
    result = render_counting(scene, *grid, settings, film, progress);
  else
#endif
    result = render_tiles(scene, settings, film, progress, [&] { return PlainQueries{accel}; });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace kappa
