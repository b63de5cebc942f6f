// The frames, one per choice of queries and accelerator type, each compiled
// in a translation unit of its own (GCC inlines less in a file with more
// render_tiles instantiations: a stats-off frame beside the counting one once
// ran 5-7 % slow). render() (integrator.cpp) picks one per frame through
// visit_accelerator.
#pragma once

#include "accel/accel.h"
#include "accel/grid.h"
#include "accel/grid2.h"
#include "renderer/render/film.h"
#include "renderer/render/frame.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// Statistics off: queries straight to a grid (render_plain_grid.cpp,
/// render_plain_grid2.cpp) or
/// through the interface (render_plain.cpp).
RenderResult render_plain(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                          const ProgressCallback& progress);
RenderResult render_plain(const Scene& scene, const NestedGrid& grid, const RenderSettings& settings, Film& film,
                          const ProgressCallback& progress);
RenderResult render_plain(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                          const ProgressCallback& progress);

/// Statistics on with a grid: its walk with per-class counters, per cell
/// and in total (render_counting.h).
RenderResult render_counting(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress);
RenderResult render_counting(const Scene& scene, const NestedGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress);

/// Statistics on with another accelerator: per class only the rays, their
/// hits and their sampled time (render_counting_classes.cpp).
RenderResult render_counting_classes(const Scene& scene, const Accelerator& accel, const RenderSettings& settings,
                                     Film& film, const ProgressCallback& progress);

}  // namespace kappa
