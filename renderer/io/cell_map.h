// `--cell-map`: where rays and triangles collude, as images of the grid.
#pragma once

#include <filesystem>

#include "accel/cell_layout.h"
#include "renderer/io/atomic_file.h"
#include "stats/render_counters.h"

namespace kappa {

/// Sums p_i (all ray classes) and Theta_i of the cells along `axis` (0 = x,
/// 1 = y, 2 = z) into an image of the other two axes, one pixel per cell of
/// the smallest size, each cell spreading its values evenly over the pixels
/// its box covers (a uniform grid: one pixel per column of cells; grid2's
/// larger leaves: several), so the image sums to p_tot and Theta_tot. An .exr gets
/// the raw sums as channels "p" and "theta"; a .png shows p in red and Theta
/// in green, each scaled by its square root to its maximum, so yellow marks
/// cells that are both visited and occupied. The format follows the target's
/// extension (checked by the caller); `counters` must hold per-cell counts.
/// Commits `out`; throws InputError.
void write_cell_map(AtomicOutput& out, const CellLayout& cells, const RenderCounters& counters, int axis);

}  // namespace kappa
