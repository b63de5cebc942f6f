// The tile loop of a frame, for one choice of queries: each translation unit
// that renders instantiates it once, so the plain frame (integrator.cpp) is
// compiled alone, exactly as in a build without statistics, and the counting
// frame (render_counting.h) beside it. Inside, one loop per sampler and
// integrator variant (path_variant.h), the pair chosen once per frame. A
// frame runs in passes: one of settings.spp, or as many as a PassControl's
// planner asks for.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "core/thread_limit.h"
#include "renderer/render/camera.h"
#include "renderer/render/frame_accumulator.h"
#include "renderer/render/frame_progress.h"
#include "renderer/render/path_tracer.h"
#include "renderer/render/samplers.h"
#include "renderer/render/tile_schedule.h"

namespace kappa {

/// The tile loop, for one choice of queries. `make_queries` gives a thread
/// its Queries object for a tile.
template <class MakeQueries>
RenderResult render_tiles(const Scene& scene, const RenderSettings& settings, Film& film, const ProgressCallback& progress,
                          MakeQueries&& make_queries, const FrameCounters* frame_counters = nullptr) {
  const Camera camera(scene.camera, film.width, film.height);
  const PathTracer tracer(scene, settings, &camera);
  const int tiles_x = (film.width + kTileSize - 1) / kTileSize;
  const int tiles_y = (film.height + kTileSize - 1) / kTileSize;
  const std::size_t tile_count = std::size_t(tiles_x) * std::size_t(tiles_y);
  PassControl* const control = settings.passes;
  PassPlanner* const planner = control ? control->planner : nullptr;
  const std::atomic<bool>* const interrupt = control ? control->interrupt : nullptr;
  const bool adaptive = planner && planner->budget().adaptive;
  TileSchedule* const schedule = settings.tiles;

  struct Counters {
    std::uint64_t rays = 0, nonfinite = 0;
  };
  tbb::enumerable_thread_specific<Counters> counters;
  // What pixels keep between passes, only for a progressive frame: a frame
  // of one pass keeps each pixel's sums on the stack and writes its film
  // as it goes (and sums its estimate per tile, added in tile order).
  const std::unique_ptr<FrameAccumulator> acc =
      control ? std::make_unique<FrameAccumulator>(film.pixels(), settings.aov) : nullptr;
  std::vector<double> tile_estimates(control ? 0 : tile_count, 0.0);
  const bool any_aov = !film.albedo.empty() || !film.normal.empty() || !film.depth.empty() || !film.cost_cells.empty();
  // The integrator: only what the scene and the settings need (path_variant.h).
  const PathVariant variant =
      choose_path_variant(tracer.lighting(), settings.light_sampling, any_aov, settings.specialise, tracer.surfaces());
  std::atomic<bool> abandoned{false};

  // One pass: samples [first, first + count) of every pixel still sampling,
  // added to its sums in sample order. A pixel whose pass an interrupt cuts
  // short keeps its sums as they were.
  const auto run_pass_with = [&]<class Sampler, PathVariant V>(std::uint32_t first, std::uint32_t count) {
    std::atomic<std::size_t> tiles_done{0};
    const auto render_tile = [&](std::size_t tile) {
      if (abandoned.load(std::memory_order_relaxed)) return;
      Counters& local = counters.local();
      auto queries = make_queries();
      const int x0 = int(tile % std::size_t(tiles_x)) * kTileSize;
      const int y0 = int(tile / std::size_t(tiles_x)) * kTileSize;
      double tile_estimate = 0;
      for (int y = y0; y < std::min(y0 + kTileSize, film.height); ++y) {
        for (int x = x0; x < std::min(x0 + kTileSize, film.width); ++x) {
          const std::size_t pixel = std::size_t(y) * std::size_t(film.width) + std::size_t(x);
          if (acc && !acc->active(pixel)) continue;
          PixelSamples px = acc ? acc->samples(pixel) : PixelSamples{};
          PixelAovSums aovs = acc && acc->has_aovs() ? acc->aov_sums(pixel) : PixelAovSums{};
          const QueryWork before = !V.aovs || film.cost_cells.empty() ? QueryWork{} : queries.work();
          for (std::uint32_t s = first; s < first + count; ++s) {
            if (interrupt && interrupt->load(std::memory_order_relaxed)) {
              abandoned.store(true, std::memory_order_relaxed);
              local.rays += queries.rays;
              return;
            }
            Sampler sampler(settings.seed, pixel, std::uint64_t(s), std::uint32_t(settings.spp));
            queries.begin_path(pixel, std::uint64_t(s));
            const auto [fx, fy] = sampler.get2D(path_dimensions::kPixel);
            FirstHit hit;
            Vec3f L = tracer.template radiance<V>(camera.generate_ray(float(x) + fx, float(y) + fy), sampler, hit, queries);
            if (settings.test_nonfinite && settings.test_nonfinite(pixel, s)) L.x = NAN;
            if (is_finite(L)) px.add(L);
            else ++local.nonfinite;
            if constexpr (V.aovs) {
              aovs.albedo[0] += hit.albedo.x, aovs.albedo[1] += hit.albedo.y, aovs.albedo[2] += hit.albedo.z;
              aovs.normal[0] += hit.normal.x, aovs.normal[1] += hit.normal.y, aovs.normal[2] += hit.normal.z;
              if (std::isfinite(hit.depth)) {
                aovs.depth += hit.depth;
                ++aovs.depth_hits;
              }
            }
          }
          px.drawn = first + count;
          if (V.aovs && !film.cost_cells.empty()) {
            const QueryWork after = queries.work();
            aovs.cells += double(after.cells - before.cells);
            aovs.tests += double(after.tests - before.tests);
          }
          if (acc) {
            acc->samples(pixel) = px;
            if (acc->has_aovs()) acc->aov_sums(pixel) = aovs;
          } else {
            resolve_pixel(film, pixel, px, aovs);
            tile_estimate += px.relmse_estimate();
          }
        }
      }
      if (!acc) tile_estimates[tile] = tile_estimate;
      local.rays += queries.rays;
      const std::size_t done = tiles_done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (progress) progress(done, tile_count);
    };
    if (!schedule) {
      kappa::parallel_for(std::size_t(0), tile_count, render_tile);
      return;
    }
    // Each render thread takes the schedule's tiles until it has none left.
    schedule->begin_pass(tile_count);
    kappa::parallel_for(std::size_t(0), std::size_t(active_threads()), [&](std::size_t) {
      while (const std::optional<std::size_t> tile = schedule->next_tile()) render_tile(*tile);
    });
  };
  // The sampler and the integrator, chosen once per frame: each pair its own loop.
  const auto run_pass = [&](std::uint32_t first, std::uint32_t count) {
    with_path_variant(variant, [&]<PathVariant V>() {
      switch (settings.sampler) {
        case SamplerKind::independent: return run_pass_with.template operator()<IndependentSampler, V>(first, count);
        case SamplerKind::stratified: return run_pass_with.template operator()<StratifiedSampler, V>(first, count);
        case SamplerKind::sobol: return run_pass_with.template operator()<SobolSampler, V>(first, count);
      }
    });
  };
  Counters resumed_counts;  // a resumed frame's counts from before its checkpoint
  const auto totals = [&] {
    Counters sum = resumed_counts;
    counters.combine_each([&](const Counters& c) {
      sum.rays += c.rays;
      sum.nonfinite += c.nonfinite;
    });
    return sum;
  };

  RenderResult result;
  result.path_variant = path_variant_name(variant);
  Counters completed;  // as of the last completed pass
  FrameState state{0, film.pixels(), 0.0};
  if (control && control->resume) {
    resume_frame(*control, *acc, film, state, result);
    resumed_counts = completed = Counters{control->resume->rays, control->resume->nonfinite};
  }
  for (;;) {
    int count = planner ? planner->next_pass(state) : (result.passes == 0 ? settings.spp : 0);
    // Processes sharing a frame take the writer's pass: its clock decides.
    if (schedule && planner) count = int(schedule->writer_value(std::uint64_t(std::max(count, 0))));
    if (count <= 0) break;
    run_pass(std::uint32_t(state.spp), std::uint32_t(count));
    if (abandoned.load()) {
      result.interrupted = true;
      break;
    }
    ++result.passes;
    state.spp += count;
    completed = totals();
    if (schedule) {
      // The frame's pixels, estimates and counts, from every process that shares it.
      std::uint64_t counts[2] = {completed.rays, completed.nonfinite};
      schedule->end_pass(acc ? nullptr : &film, tile_estimates, counts);
      completed = Counters{counts[0], counts[1]};
      if (acc) share_pass_state(*schedule, *acc, film.width, film.height);
    }
    if (acc) {
      // The film of every completed pass, ready to be written if the next
      // is interrupted; then what the planner decides the next pass from.
      acc->resolve(film);
      if (adaptive && state.spp >= planner->budget().adaptive_min_spp)
        acc->retire_converged(planner->budget().target_relmse, std::uint32_t(planner->budget().adaptive_min_spp));
      state.active_pixels = acc->active_pixels();
      state.relmse_estimate = acc->relmse_estimate();
      result.spp_spread = acc->spp_spread();
      if (control->on_pass) control->on_pass(state, result.passes);
      if (control->checkpoint_due)
        checkpoint_if_due(*control, *acc, state, result.passes, completed.rays, completed.nonfinite, planner->elapsed(),
                          frame_counters, schedule);
    }
  }
  if (!acc) {
    double sum = 0;
    for (double e : tile_estimates) sum += e;
    state.relmse_estimate = film.pixels() > 0 ? sum / double(film.pixels()) : 0.0;
    const auto spp = std::uint32_t(state.spp);
    result.spp_spread = SppSpread{spp, spp, double(spp)};
  }

  const Counters all = schedule ? completed : totals();
  result.rays = all.rays;
  result.abandoned_rays = all.rays - completed.rays;
  result.nonfinite_samples = completed.nonfinite;
  result.spp = state.spp;
  result.relmse_estimate = state.relmse_estimate;
  if (planner) result.stop_reason = result.interrupted ? "interrupted" : planner->stop_reason();
  return result;
}

}  // namespace kappa
