// The tile loop of a frame, for one choice of queries: each translation unit
// that renders instantiates it once, so the plain frame (integrator.cpp) is
// compiled alone, exactly as in a build without statistics, and the counting
// frame (render_counting.cpp) beside it.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "renderer/render/camera.h"
#include "renderer/render/path_tracer.h"

namespace kappa {

inline constexpr int kTileSize = 16;

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
          if (!is_finite(L)) {
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

}  // namespace kappa
