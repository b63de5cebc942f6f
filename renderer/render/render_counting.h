// The frame with statistics on: the grid walked with per-class counters (or,
// for other accelerators, what applies to any).
#pragma once

#include "accel/grid.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene.h"

namespace kappa {

RenderResult render_counting(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress);

/// The frame with statistics on and another accelerator: per class only the
/// rays, their hits and their sampled time.
RenderResult render_counting_classes(const Scene& scene, const Accelerator& accel, const RenderSettings& settings,
                                     Film& film, const ProgressCallback& progress);

}  // namespace kappa
