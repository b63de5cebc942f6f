// The frame with statistics on: the grid walked with per-class counters.
#pragma once

#include "accel/grid.h"
#include "integrator.h"

namespace kappa {

RenderResult render_counting(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress);

}  // namespace kappa
