// The stats-off frame of the accelerators without an instantiation of their
// own (naive, Embree): every query through the Accelerator interface.
#include "renderer/render/frames.h"
#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"

namespace kappa {

RenderResult render_plain(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                          const ProgressCallback& progress) {
  return render_tiles(scene, settings, film, progress, [&] { return PlainQueries<Accelerator>{accel}; });
}

}  // namespace kappa
