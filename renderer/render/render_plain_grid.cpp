// The grid's stats-off frame: every query calls UniformGrid directly (a final
// class: no virtual call reaches its per-ray loop), alone in its translation
// unit as in a build without statistics.
#include "accel/grid_traverse.h"  // the filtered walk (cut-outs) is instantiated here
#include "renderer/render/frames.h"
#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"

namespace kappa {

RenderResult render_plain(const Scene& scene, const UniformGrid& grid, const RenderSettings& settings, Film& film,
                          const ProgressCallback& progress) {
  return render_tiles(scene, settings, film, progress, [&] {
    return PlainQueries<UniformGrid>{grid, settings.occluder_cache};
  });
}

}  // namespace kappa
