// The grids' frames with statistics on: their walks instantiated with per-class
// counters, per cell (every path into per-thread arrays, or sampled paths
// into one shared set) and in total, within --grid-max-bytes (plan_per_cell).
// Instantiated once per grid, each in its own translation unit
// (render_counting_grid.cpp, render_counting_grid2.cpp): the frame's
// variants x samplers x per-cell modes made one file the build's longest.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/thread_limit.h"
#include "renderer/render/frame_progress.h"
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
  const std::uint64_t sets = lobes ? kCountedSets : kRenderClasses;
  PerCellPlan plan = plan_per_cell(n, sets, std::uint64_t(active_threads()), asked, grid.bytes(), settings.stats_max_bytes);
  // A resumed frame adds to its checkpoint's counters: it counts per cell
  // as they were counted.
  const FrameProgress* const resumed = settings.passes ? settings.passes->resume : nullptr;
  if (resumed && !resumed->counters.empty() && resumed->cell_sample != (plan.mode == PerCell::no ? 0 : plan.every)) {
    const std::uint64_t every = resumed->cell_sample;
    plan = every == 0 ? PerCellPlan{PerCell::no, 1, 0, plan.note}
                      : plan_per_cell(n, sets, std::uint64_t(active_threads()), every, grid.bytes(), settings.stats_max_bytes);
    if (every != 0 && (plan.mode == PerCell::no || plan.every != every))
      throw InputError("per-cell statistics: the checkpoint counted 1 path in " + std::to_string(every) +
                               " per cell, which this run cannot within --grid-max-bytes");
  }
  if (TileSchedule* const split = settings.tiles) {
    // A frame shared by processes counts per cell as its writer does (the
    // same paths: 1 in the writer's rate, or none), whatever each process's
    // threads and memory would choose alone, so that their counts add up to
    // those of the writer's frame. 0: no per-cell counts.
    const std::uint64_t every = split->writer_value(plan.mode == PerCell::no ? 0 : plan.every);
    if (every == 0 && plan.mode != PerCell::no) plan = PerCellPlan{PerCell::no, 1, 0, plan.note};
    else if (every != 0 && (plan.mode == PerCell::no || plan.every != every))
      plan = plan_per_cell(n, sets, std::uint64_t(active_threads()), every, grid.bytes(), settings.stats_max_bytes);
    // A process that cannot count as the writer does cannot add its counts.
    if (every != 0 && (plan.mode == PerCell::no || plan.every != every))
      throw std::runtime_error("per-cell statistics: this rank cannot count 1 path in " + std::to_string(every) +
                               " within --grid-max-bytes as rank 0 does");
  }
  const CellSampling sampling{plan.every, settings.seed};
  const SharedCellArrays shared =
      plan.mode == PerCell::shared ? make_shared_cell_arrays(n, lobes) : SharedCellArrays{};
  tbb::enumerable_thread_specific<RenderCounters> per_thread([&] {
    return shared[0] ? RenderCounters(shared, size) : RenderCounters(n, size, plan.mode == PerCell::own, lobes);
  });
  // Counters of this frame's shape, zero: what a process given no tile
  // adds, and what a checkpoint's sum of the threads' starts from (the
  // threads' own arrays added in, shared ones held once).
  const auto zero_counters = [&] {
    return shared[0] ? RenderCounters(shared, size) : RenderCounters(n, size, plan.mode == PerCell::own, lobes);
  };
  const FrameCounters frame_counters{[&] {
                                       RenderCounters sum = zero_counters();
                                       for (const RenderCounters& c : per_thread) sum.merge(c);
                                       return sum.flatten();
                                     },
                                     plan.mode == PerCell::no ? 0 : plan.every};
  RenderResult result;
  if (shared[0])
    result = render_tiles(
        scene, settings, film, progress,
        [&] { return CountingQueries<Walker, PerCell::shared>(grid, per_thread.local(), sampling, settings.occluder_cache); },
        &frame_counters);
  else
    result = render_tiles(
        scene, settings, film, progress,
        [&] { return CountingQueries<Walker, PerCell::own>(grid, per_thread.local(), sampling, settings.occluder_cache); },
        &frame_counters);
  // Merge into one thread's counters: no further copy of the arrays (and
  // none at all of shared ones).
  std::shared_ptr<RenderCounters> merged;
  for (RenderCounters& c : per_thread) {
    if (!merged) merged = std::make_shared<RenderCounters>(std::move(c));
    else merged->merge(c);
  }
  if (!merged)  // no tile rendered here (a rank given none): counts of the same shape, zero
    merged = std::make_shared<RenderCounters>(zero_counters());
  if (settings.tiles || (resumed && !resumed->counters.empty())) {
    // Every process's counts, summed into the writer's, and a checkpoint's
    // (the writer's resume alone has them).
    std::vector<std::uint64_t> flat = merged->flatten();
    if (settings.tiles) settings.tiles->sum_on_writer(flat);
    if (resumed && !resumed->counters.empty()) {
      if (resumed->counters.size() != flat.size())
        throw std::runtime_error("statistics: the checkpoint's counters are not this frame's (" +
                                 std::to_string(resumed->counters.size()) + " counts, here " + std::to_string(flat.size()) + ")");
      for (std::size_t i = 0; i < flat.size(); ++i) flat[i] += resumed->counters[i];
    }
    merged->assign(flat);
  }
  result.counters = merged;
  result.cell_sample = plan.every;
  result.stats_note = plan.note;
  return result;
}

}  // namespace kappa::detail
