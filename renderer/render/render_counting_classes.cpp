// The frame with statistics on and an accelerator without cells (naive,
// Embree), in its own translation unit (frames.h says why).
#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <vector>

#include "renderer/render/queries.h"
#include "stats/query_clock.h"
#include "renderer/render/frames.h"
#include "renderer/render/tile_loop.h"

namespace kappa {

RenderResult render_counting_classes(const Scene& scene, const Accelerator& accel, const RenderSettings& settings,
                                     Film& film, const ProgressCallback& progress) {
  QueryClock::get();  // its one-time set-up (about 25 ms) stays out of the frame's time
  const bool lobes = scene.has_materials();  // counted apart only where a surface is not Lambertian (RenderCounters)
  tbb::enumerable_thread_specific<RenderCounters> per_thread([&] { return RenderCounters(0, Vec3d{}, false, lobes); });
  RenderResult result = render_tiles(scene, settings, film, progress,
                                     [&] { return ClassQueries(accel, per_thread.local()); });
  auto merged = std::make_shared<RenderCounters>(0, Vec3d{}, false, lobes);
  for (const RenderCounters& c : per_thread) merged->merge(c);
  if (TileSchedule* const split = settings.tiles) {
    // Every process's counts, summed into the writer's (render_counting.h).
    std::vector<std::uint64_t> flat = merged->flatten();
    split->sum_on_writer(flat);
    merged->assign(flat);
  }
  result.counters = merged;
  return result;
}

}  // namespace kappa
