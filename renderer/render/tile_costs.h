// What each of a frame's tiles is predicted to cost, from the pilot of
// --accel auto or --grid-res model (pilot.h): a frame shared by processes
// hands out its first pass's tiles the costliest first, so that the last
// ones handed out, which decide when the slowest process ends, are cheap
// (issue 48). Later passes go by the seconds each tile took in the pass
// before, measured (renderer/mpi/mpi_frame_split.cpp).
#pragma once

#include <cstddef>
#include <vector>

namespace kappa {

struct Pilot;

/// By tile (kTileSize squares, row by row): the pilot's queries over the
/// tile's pixels, each frame pixel taking the pilot pixel it falls in (one
/// sample each). Queries, not the pilot's seconds: timed, a 1-sample path
/// carries the frame's first page faults and preemptions, and the predicted
/// costs' (Pearson) correlation with the tiles' measured seconds was 0.04 on Sponza
/// (512², 2 ranks), 0.45 on the bunny; counted, 0.72–0.84 and 0.90 (the
/// dragon 0.86). Empty when
/// the pilot counted no pixel.
std::vector<double> predicted_tile_costs(const Pilot& pilot, int width, int height);

/// The tiles, costliest first (ties, and a cost missing, in tile order).
std::vector<std::size_t> costliest_first(const std::vector<double>& costs, std::size_t tiles);

}  // namespace kappa
