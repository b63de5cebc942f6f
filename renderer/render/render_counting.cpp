#include "renderer/render/render_counting.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

#include "accel/byte_size.h"
#include "accel/thread_limit.h"
#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"

namespace kappa {

RenderResult render_counting(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress) {
  RenderResult result;
  // Per-cell arrays per class and per thread must fit beside the grid in
  // --grid-max-bytes, with what the report adds (64-bit visits folded per
  // class, and one 64-bit array for the classes together); otherwise only
  // per-class totals are kept.
  const std::uint64_t cells = grid.info().resolution.cells();
  const std::uint64_t threads = std::uint64_t(active_threads());  // the caller's ThreadLimit
  const std::uint64_t every = settings.cell_sample > 0 ? settings.cell_sample : auto_cell_sample(cells);
  // Counting every path writes at every step: each thread gets arrays of its
  // own. Sampled paths write rarely: one set of arrays for all threads.
  const bool share = every > 1;
  const std::uint64_t need = per_cell_stats_bytes(cells, share ? 1 : threads);
  const bool per_cell = grid.info().bytes + need <= settings.stats_max_bytes;
  const CellSampling sampling{per_cell ? every : 1, settings.seed};
  const SharedCellArrays shared = per_cell && share ? make_shared_cell_arrays(cells) : SharedCellArrays{};
  tbb::enumerable_thread_specific<RenderCounters> per_thread([&] {
    return shared[0] ? RenderCounters(shared) : RenderCounters(grid.info().resolution, per_cell);
  });
  if (shared[0])
    result = render_tiles(scene, settings, film, progress, [&] {
      return CountingQueries<PerCell::shared>(grid, per_thread.local(), sampling);
    });
  else
    result = render_tiles(scene, settings, film, progress,
                          [&] { return CountingQueries<PerCell::own>(grid, per_thread.local(), sampling); });
  // Merge into one thread's counters: no further copy of the arrays (and
  // none at all of shared ones).
  std::shared_ptr<RenderCounters> merged;
  for (RenderCounters& c : per_thread) {
    if (!merged) merged = std::make_shared<RenderCounters>(std::move(c));
    else merged->merge(c);
  }
  if (!merged) merged = std::make_shared<RenderCounters>(grid.info().resolution, per_cell);
  result.counters = merged;
  result.cell_sample = sampling.every;
  if (!per_cell)
    result.stats_note = "per-cell statistics refused: " + byte_size(need) + " of counters and " +
                        byte_size(grid.info().bytes) + " of grid would exceed --grid-max-bytes (" +
                        byte_size(settings.stats_max_bytes) + "); per-class totals only";
  return result;
}

}  // namespace kappa
