#include "renderer/render/integrator.h"

#include <chrono>
#include <type_traits>

#include "accel/dispatch.h"
#include "renderer/render/frames.h"
#include "renderer/render/occluder_cache.h"
#include "renderer/render/statistics_built.h"

namespace kappa {

RenderResult render(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                    const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  // The one per-frame choice: the accelerator's concrete type and the queries.
  bool cached = false;
  RenderResult result = visit_accelerator(accel, [&](const auto& a) {
    using A = std::decay_t<decltype(a)>;
    cached = settings.occluder_cache && OccluderWalker<A>;
#ifndef KAPPA_NO_STATS  // kappa-nostats has no trace of them: no call, so no counting code linked
    if (settings.stats) {
      if constexpr (CellWalker<A>) return render_counting(scene, a, settings, film, progress);
      else return render_counting_classes(scene, a, settings, film, progress);
    }
#endif
    return render_plain(scene, a, settings, film, progress);
  });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.occluder_cache = cached;
  return result;
}

bool statistics_built() {
#ifdef KAPPA_NO_STATS
  return false;
#else
  return true;
#endif
}

}  // namespace kappa
