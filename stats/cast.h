// Casting a set of rays through the uniform grid with per-cell counters on:
// the measurement behind `kappa cast` and the model's identity tests.
#pragma once

#include <cstdint>
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
};

/// Walks every ray (to its closest hit, to any hit, or along its whole
/// chord) with thread-local counters merged once at the end; `threads` = 0
/// uses every core. Totals do not depend on the thread count.
CastMeasurement cast_with_counters(const UniformGrid& grid, std::span<const Ray> rays, GridWalk walk, int threads = 0);

/// Theta_i of every cell of `grid`.
std::vector<std::uint32_t> occupancies(const UniformGrid& grid);

}  // namespace kappa
