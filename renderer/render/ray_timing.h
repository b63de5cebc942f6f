// Timing a fixed ray set through an accelerator, as a stats-off render makes
// its queries: what `kappa bench` and `kappa sweep` measure while the
// configurations they compare take turns.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "renderer/render/ray_sets.h"

namespace kappa {

/// Seconds to trace every ray of `set` once in `arena`, each query made as
/// the render's stats-off frame makes it (the accelerator as
/// visit_accelerator gives it); `hits` gets the rays that hit.
template <class A>
double time_pass(const A& accel, const RaySet& set, tbb::task_arena& arena, std::uint64_t& hits) {
  std::atomic<std::uint64_t> found{0};
  const auto start = std::chrono::steady_clock::now();
  arena.execute([&] {
    kappa::parallel_for(tbb::blocked_range<std::size_t>(0, set.rays.size(), 4096), [&](const auto& range) {
      std::uint64_t local = 0;
      if (set.occlusion) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) local += accel.any_hit(set.rays[i]);
      } else {
        for (std::size_t i = range.begin(); i < range.end(); ++i) local += accel.closest_hit(set.rays[i]).has_value();
      }
      found.fetch_add(local, std::memory_order_relaxed);
    });
  });
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  hits = found.load();
  return s;
}

/// The median (the mean of the middle two for an even count); 0 for none.
inline double median_of(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace kappa
