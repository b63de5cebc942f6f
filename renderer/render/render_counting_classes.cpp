// The frame with statistics on and an accelerator other than the grid. Its
// own translation unit: GCC inlines less in a file with more render_tiles
// instantiations (a stats-off frame beside the counting one once ran 5-7 %
// slow), so the grid's counting file keeps only its own two.
#include <tbb/enumerable_thread_specific.h>

#include <memory>

#include "renderer/render/queries.h"
#include "renderer/render/render_counting.h"
#include "renderer/render/tile_loop.h"

namespace kappa {

RenderResult render_counting_classes(const Scene& scene, const Accelerator& accel, const RenderSettings& settings,
                                     Film& film, const ProgressCallback& progress) {
  tbb::enumerable_thread_specific<RenderCounters> per_thread([] { return RenderCounters(GridResolution{}, false); });
  RenderResult result = render_tiles(scene, settings, film, progress,
                                     [&] { return ClassQueries(accel, per_thread.local()); });
  auto merged = std::make_shared<RenderCounters>(GridResolution{}, false);
  for (const RenderCounters& c : per_thread) merged->merge(c);
  result.counters = merged;
  return result;
}

}  // namespace kappa
