// The frame with statistics on and an accelerator without cells (naive,
// Embree), in its own translation unit (frames.h says why).
#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "renderer/render/frame_progress.h"
#include "renderer/render/frames.h"
#include "renderer/render/queries.h"
#include "renderer/render/tile_loop.h"
#include "stats/query_clock.h"

namespace kappa {

RenderResult render_counting_classes(const Scene& scene, const Accelerator& accel, const RenderSettings& settings,
                                     Film& film, const ProgressCallback& progress) {
  QueryClock::get();  // its one-time set-up (about 25 ms) stays out of the frame's time
  const bool lobes = scene.has_materials();  // counted apart only where a surface is not Lambertian (RenderCounters)
  tbb::enumerable_thread_specific<RenderCounters> per_thread([&] { return RenderCounters(0, Vec3d{}, false, lobes); });
  const FrameCounters frame_counters{[&] {
                                       RenderCounters sum(0, Vec3d{}, false, lobes);
                                       for (const RenderCounters& c : per_thread) sum.merge(c);
                                       return sum.flatten();
                                     },
                                     0};
  RenderResult result = render_tiles(
      scene, settings, film, progress, [&] { return ClassQueries(accel, per_thread.local()); }, &frame_counters);
  auto merged = std::make_shared<RenderCounters>(0, Vec3d{}, false, lobes);
  for (const RenderCounters& c : per_thread) merged->merge(c);
  const FrameProgress* const resumed = settings.passes ? settings.passes->resume : nullptr;
  if (settings.tiles || (resumed && !resumed->counters.empty())) {
    // Every process's counts, summed into the writer's (render_counting.h),
    // and a checkpoint's.
    std::vector<std::uint64_t> flat = merged->flatten();
    if (settings.tiles) settings.tiles->sum_on_writer(flat);
    if (resumed && !resumed->counters.empty()) {
      if (resumed->counters.size() != flat.size())
        throw std::runtime_error("statistics: the checkpoint's counters are not this frame's");
      for (std::size_t i = 0; i < flat.size(); ++i) flat[i] += resumed->counters[i];
    }
    merged->assign(flat);
  }
  result.counters = merged;
  return result;
}

}  // namespace kappa
