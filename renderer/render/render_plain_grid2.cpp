// grid2's stats-off frame: every query calls NestedGrid directly (a final
// class), alone in its translation unit as the uniform grid's frame is.
#include "accel/grid2_traverse.h"
#include "renderer/render/frames.h"
#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"

namespace kappa {

RenderResult render_plain(const Scene& scene, const NestedGrid& grid, const RenderSettings& settings, Film& film,
                          const ProgressCallback& progress) {
  return render_tiles(scene, settings, film, progress, [&] {
    return PlainQueries<NestedGrid>{grid, settings.occluder_cache};
  });
}

}  // namespace kappa
