#include "renderer/render/integrator.h"

#include <chrono>

#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"
#ifndef KAPPA_NO_STATS
#include "renderer/render/render_counting.h"
#endif

namespace kappa {

RenderResult render(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                    const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  RenderResult result;
#ifndef KAPPA_NO_STATS  // a build without statistics has no trace of them here (render_counting.cpp)
  if (const auto* grid = dynamic_cast<const UniformGrid*>(&accel); settings.stats && grid)
    result = render_counting(scene, *grid, settings, film, progress);
  else if (settings.stats)
    result = render_counting_classes(scene, accel, settings, film, progress);
  else
#endif
    result = render_tiles(scene, settings, film, progress, [&] { return PlainQueries{accel}; });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace kappa
