// Casting a set of rays through the uniform grid with per-cell counters on:
// the measurement behind `kappa cast` and the model's identity tests.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <span>
#include <vector>

#include "accel/grid.h"
#include "collusion.h"
#include "counters.h"

namespace kappa {

struct CastMeasurement {
  CellCounters counters{GridResolution{}, false};
  std::vector<std::uint32_t> theta;  ///< Theta_i, from the grid
  CollusionStats collusion;
  double cells_per_ray_predicted = 0;  ///< mean over rays of 1 + sum_a |d_a| len / l_a (eq 24 per axis)
  double time_s = 0;                   ///< wall time of the cast with counters on
  std::string stats_note;              ///< why per-cell counts were refused, if they were
};

/// Memory for per-cell counts of a cast on a grid of `cells` cells with
/// `threads` threads: per thread 64-bit visits, tests and hits, plus the
/// merged copy and, for the report, Theta_i and 64-bit visits.
inline std::uint64_t cast_per_cell_bytes(std::uint64_t cells, std::uint64_t threads) {
  return cells * (24 * (threads + 1) + 4 + 8);
}

/// Walks every ray (to its closest hit, to any hit, or along its whole
/// chord) with thread-local counters merged once at the end, on as many
/// threads as the caller's ThreadLimit allows (accel/thread_limit.h).
/// Totals do not depend on the thread count. When the grid
/// and the per-cell counts (cast_per_cell_bytes) would exceed `max_bytes`,
/// only totals are counted (stats_note says so): p_tot, refs_per_ray and
/// kappa (eq 8) stay exact, sigma_p, r and kappa_eq25 are undefined.
CastMeasurement cast_with_counters(const UniformGrid& grid, std::span<const Ray> rays, GridWalk walk,
                                   std::uint64_t max_bytes = std::numeric_limits<std::uint64_t>::max());

/// Theta_i of every cell of `grid`.
std::vector<std::uint32_t> occupancies(const UniformGrid& grid);

}  // namespace kappa
