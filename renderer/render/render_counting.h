// The grids' frames with statistics on: their walks instantiated with per-class
// counters, per cell (every path into per-thread arrays, or sampled paths
// into one shared set) and in total, within --grid-max-bytes (plan_per_cell).
// Instantiated once per grid, each in its own translation unit
// (render_counting_grid.cpp, render_counting_grid2.cpp): the frame's
// variants x samplers x per-cell modes made one file the build's longest.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <memory>

#include "core/thread_limit.h"
#include "renderer/render/frames.h"
#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"
#include "stats/per_cell_budget.h"
#include "stats/query_clock.h"

namespace kappa::detail {

template <class Walker>
RenderResult render_counting_with(const Scene& scene, const Walker& grid, const RenderSettings& settings, Film& film,
                                  const ProgressCallback& progress) {
  QueryClock::get();  // its one-time set-up (about 25 ms) stays out of the frame's time
  const CellLayout& cells = *grid.cells();
  const std::uint64_t n = cells.cell_count();
  const Vec3d size = cells.uniform_cell_size().value_or(Vec3d{});
  const std::uint64_t asked = settings.cell_sample > 0 ? settings.cell_sample : auto_cell_sample(n);
  // Lobes are counted apart only where a surface is not Lambertian (RenderCounters).
  const bool lobes = scene.has_materials();
  const PerCellPlan plan = plan_per_cell(n, lobes ? kCountedSets : kRenderClasses, std::uint64_t(active_threads()),
                                         asked, grid.bytes(), settings.stats_max_bytes);
  const CellSampling sampling{plan.every, settings.seed};
  const SharedCellArrays shared =
      plan.mode == PerCell::shared ? make_shared_cell_arrays(n, lobes) : SharedCellArrays{};
  tbb::enumerable_thread_specific<RenderCounters> per_thread([&] {
    return shared[0] ? RenderCounters(shared, size) : RenderCounters(n, size, plan.mode == PerCell::own, lobes);
  });
  RenderResult result;
  if (shared[0])
    result = render_tiles(scene, settings, film, progress, [&] {
      return CountingQueries<Walker, PerCell::shared>(grid, per_thread.local(), sampling, settings.occluder_cache);
    });
  else
    result = render_tiles(scene, settings, film, progress, [&] {
      return CountingQueries<Walker, PerCell::own>(grid, per_thread.local(), sampling, settings.occluder_cache);
    });
  // Merge into one thread's counters: no further copy of the arrays (and
  // none at all of shared ones).
  std::shared_ptr<RenderCounters> merged;
  for (RenderCounters& c : per_thread) {
    if (!merged) merged = std::make_shared<RenderCounters>(std::move(c));
    else merged->merge(c);
  }
  if (!merged) merged = std::make_shared<RenderCounters>(n, size, plan.mode == PerCell::own, lobes);
  result.counters = merged;
  result.cell_sample = plan.every;
  result.stats_note = plan.note;
  return result;
}

}  // namespace kappa::detail
