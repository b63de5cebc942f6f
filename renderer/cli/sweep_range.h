// Where `kappa sweep` measures: resolutions geometric in N_c over a range of
// densities (lambda, N_c = lambda N) or of cubic resolutions (N_c = r^3),
// each made of near-cubic cells as --grid-res auto makes them.
#pragma once

#include <string>
#include <vector>

#include "accel/grid_resolution.h"
#include "core/vec3.h"

namespace kappa {

/// A range "A:B" with 0 < A <= B, both finite. Throws InputError naming `flag`.
struct SweepRange {
  double from = 0, to = 0;
};
SweepRange parse_sweep_range(const std::string& text, const std::string& flag);

/// `steps` target cell counts from `from_cells` to `to_cells`, geometric
/// (one point: `from_cells`), turned into resolutions over `extent` by
/// choose_resolution; a resolution two targets share is listed once.
std::vector<GridResolution> sweep_resolutions(const Vec3d& extent, double from_cells, double to_cells, int steps);

}  // namespace kappa
