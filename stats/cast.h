// Casting a set of rays through a cell-based accelerator with per-cell
// counters on: the measurement behind `kappa cast`, the calibration's counts
// and the model's identity tests. The walk is the accelerator's own,
// instantiated with stats' recorders (accel/recorder.h); cells are read
// through its CellLayout.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "accel/cell_layout.h"
#include "accel/ray.h"
#include "accel/recorder.h"
#include "collusion.h"
#include "core/hash.h"
#include "core/parallel.h"
#include "core/thread_limit.h"
#include "counters.h"
#include "per_cell_budget.h"

namespace kappa {

struct CastMeasurement {
  CellCounters counters{0, Vec3d{}, false};
  std::vector<std::uint32_t> theta;  ///< Theta_i, from the layout
  CollusionStats collusion;          ///< exact when every ray was counted per cell, else estimated (collusion_sampled)
  CollusionStats sample;             ///< the per-cell sample alone (collusion over its rays); N_r = 0 without one
  double cells_per_ray_predicted = 0;  ///< mean over rays of eq 24 for the walked segment
  double time_s = 0;                   ///< wall time of the cast with counters on
  std::uint64_t cell_sample = 1;       ///< 1 ray in this many was counted per cell
  std::string stats_note;              ///< why per-cell counts were sampled or refused, if they were
};

/// Which rays of a cast count per cell when only 1 in `every` does: drawn by
/// a hash of the ray's index, so the choice does not depend on the thread count.
inline bool counts_ray(std::uint64_t index, std::uint64_t every) {
  return every <= 1 || mix64(index ^ 0x63617374ull) % every == 0;  // "cast"
}

/// The counts, collusion and predictions of a finished cast (cast.cpp).
CastMeasurement finish_cast(const CellLayout& cells, CellCounters counters, const PerCellPlan& plan, double seconds);

namespace detail {

/// Walks `rays` (to the closest hit, any hit or along the whole chord: a
/// template argument, not a branch per ray) with one tally per ray into
/// thread-local counters; per cell only for the rays the plan counts.
template <GridWalk Walk, PerCell Mode, class Walker>
void walk_all(const Walker& walker, std::span<const Ray> rays, std::uint64_t every,
              tbb::enumerable_thread_specific<CellCounters>& per_thread) {
  kappa::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
    CellCounters& counters = per_thread.local();
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const auto walk = [&](auto& tally) {
        if constexpr (Walk == GridWalk::closest) return walker.closest_hit(rays[i], tally).has_value();
        else if constexpr (Walk == GridWalk::any) return walker.any_hit(rays[i], tally);
        else return walker.walk_whole(rays[i], tally).has_value();
      };
      bool hit = false;
      if constexpr (Mode != PerCell::no) {
        if (counts_ray(i, every)) {
          CellCounters::BasicTally<Mode> tally(counters);
          hit = walk(tally);
        } else {
          CellCounters::TotalsTally tally(counters);
          hit = walk(tally);
        }
      } else {
        CellCounters::TotalsTally tally(counters);
        hit = walk(tally);
      }
      ++counters.totals.rays;
      counters.totals.hits += hit;
    }
  });
}

template <PerCell Mode, class Walker>
void walk_all(const Walker& walker, std::span<const Ray> rays, GridWalk walk, std::uint64_t every,
              tbb::enumerable_thread_specific<CellCounters>& per_thread) {
  switch (walk) {
    case GridWalk::closest: walk_all<GridWalk::closest, Mode>(walker, rays, every, per_thread); break;
    case GridWalk::any: walk_all<GridWalk::any, Mode>(walker, rays, every, per_thread); break;
    case GridWalk::whole: walk_all<GridWalk::whole, Mode>(walker, rays, every, per_thread); break;
  }
}

}  // namespace detail

/// Walks every ray (to its closest hit, to any hit, or along its whole
/// chord) of a CellWalker (accel/dispatch.h) with thread-local counters
/// merged once at the end, on as many threads as the caller's ThreadLimit
/// allows (core/thread_limit.h). Totals do not depend on the thread count.
/// Per-cell counts follow plan_per_cell within `max_bytes` beside the
/// walker's structure: every ray into per-thread arrays, or 1 ray in 64 into
/// one shared set (stats_note says so), or none (p_tot, refs_per_ray and
/// kappa by eq 8 stay exact; sigma_p, r and kappa_eq25 are undefined).
template <class Walker>
CastMeasurement cast_with_counters(const Walker& walker, std::span<const Ray> rays, GridWalk walk,
                                   std::uint64_t max_bytes = std::numeric_limits<std::uint64_t>::max()) {
  const CellLayout& cells = *walker.cells();
  const std::uint64_t n = cells.cell_count();
  const Vec3d size = cells.uniform_cell_size().value_or(Vec3d{});
  const auto start = std::chrono::steady_clock::now();
  const PerCellPlan plan = plan_per_cell(n, 1, std::uint64_t(active_threads()), 1, walker.bytes(), max_bytes);
  const auto shared = plan.mode == PerCell::shared ? std::make_shared<CellArrays>(n) : nullptr;
  tbb::enumerable_thread_specific<CellCounters> per_thread([&] {
    return shared ? CellCounters(shared, size) : CellCounters(n, size, plan.mode == PerCell::own);
  });
  switch (plan.mode) {
    case PerCell::own: detail::walk_all<PerCell::own>(walker, rays, walk, plan.every, per_thread); break;
    case PerCell::shared: detail::walk_all<PerCell::shared>(walker, rays, walk, plan.every, per_thread); break;
    case PerCell::no: detail::walk_all<PerCell::no>(walker, rays, walk, plan.every, per_thread); break;
  }
  CellCounters merged = shared ? CellCounters(shared, size) : CellCounters(n, size, plan.mode == PerCell::own);
  per_thread.combine_each([&](const CellCounters& c) { merged.merge(c); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return finish_cast(cells, std::move(merged), plan, seconds);
}

}  // namespace kappa
