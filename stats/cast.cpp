#include "cast.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "accel/byte_size.h"
#include "accel/grid_traverse.h"
#include "accel/thread_limit.h"
#include "cost_model.h"

namespace kappa {

std::vector<std::uint32_t> occupancies(const UniformGrid& grid) {
  std::vector<std::uint32_t> theta(grid.info().resolution.cells());
  for (std::uint64_t c = 0; c < theta.size(); ++c) theta[c] = std::uint32_t(grid.cell(c).size());
  return theta;
}

namespace {

/// Walks `rays` (to the closest hit, any hit or along the whole chord: a
/// template argument, not a branch per ray) with one Tally (per-cell or
/// totals-only) per ray into thread-local counters.
template <GridWalk Walk, class Tally>
void walk_all(const UniformGrid& grid, std::span<const Ray> rays,
              tbb::enumerable_thread_specific<CellCounters>& per_thread) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
    CellCounters& counters = per_thread.local();
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      Tally tally(counters);
      bool hit = false;
      if constexpr (Walk == GridWalk::closest) hit = grid.closest_hit(rays[i], tally).has_value();
      else if constexpr (Walk == GridWalk::any) hit = grid.any_hit(rays[i], tally);
      else hit = grid.walk_whole(rays[i], tally).has_value();
      ++counters.totals.rays;
      counters.totals.hits += hit;
    }
  });
}

template <class Tally>
void walk_all(const UniformGrid& grid, std::span<const Ray> rays, GridWalk walk,
              tbb::enumerable_thread_specific<CellCounters>& per_thread) {
  switch (walk) {
    case GridWalk::closest: walk_all<GridWalk::closest, Tally>(grid, rays, per_thread); break;
    case GridWalk::any: walk_all<GridWalk::any, Tally>(grid, rays, per_thread); break;
    case GridWalk::whole: walk_all<GridWalk::whole, Tally>(grid, rays, per_thread); break;
  }
}

}  // namespace

CastMeasurement cast_with_counters(const UniformGrid& grid, std::span<const Ray> rays, GridWalk walk,
                                   std::uint64_t max_bytes) {
  const auto start = std::chrono::steady_clock::now();
  const GridResolution res = grid.info().resolution;
  const std::uint64_t workers = std::uint64_t(active_threads());
  const std::uint64_t need = cast_per_cell_bytes(res.cells(), workers);
  const bool per_cell = need <= max_bytes && grid.info().bytes <= max_bytes - need;
  tbb::enumerable_thread_specific<CellCounters> per_thread([&] { return CellCounters(res, per_cell); });
  if (per_cell) walk_all<CellCounters::Tally>(grid, rays, walk, per_thread);
  else walk_all<CellCounters::TotalsTally>(grid, rays, walk, per_thread);
  CastMeasurement m;
  m.counters = CellCounters(res, per_cell);
  per_thread.combine_each([&](const CellCounters& c) { m.counters.merge(c); });
  m.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  m.theta = occupancies(grid);
  const ClassTotals& t = m.counters.totals;
  if (per_cell) {
    m.collusion = collusion(m.counters.visits(), m.theta, t.rays);
  } else {
    m.collusion = collusion_sampled({}, m.theta, 0, t.rays, t.cells, t.refs);
    m.stats_note = "per-cell statistics refused: " + byte_size(need) + " of counters and " +
                   byte_size(grid.info().bytes) + " of grid would exceed --grid-max-bytes (" + byte_size(max_bytes) +
                   "); per-class totals only";
  }

  // Predicted cells per ray from each ray's own length inside the grid box,
  // summed by the walks (WalkCounts::predicted_cells).
  m.cells_per_ray_predicted = rays.empty() ? 0.0 : t.predicted_cells() / double(rays.size());
  return m;
}

}  // namespace kappa
