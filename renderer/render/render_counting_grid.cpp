// The grid's frame with statistics on (render_counting.h).
#include "accel/grid_traverse.h"
#include "renderer/render/render_counting.h"

namespace kappa {

RenderResult render_counting(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                             const ProgressCallback& progress) {
  return detail::render_counting_with(scene, grid, settings, film, progress);
}

}  // namespace kappa
