// Unidirectional path tracing with next-event estimation (emissive triangles
// and the constant environment, chosen by power), multiple importance sampling
// with the power heuristic, and Russian roulette.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "accel/accel.h"
#include "stats/render_counters.h"
#include "film.h"
#include "scene.h"

namespace kappa {

struct RenderSettings {
  int spp = 16;
  int max_depth = 32;       ///< bounces after the camera ray; 1 = direct lighting only
  int rr_depth = 3;         ///< Russian roulette from this many bounces on; < 0 disables it
  std::uint64_t seed = 0;
  int threads = 0;          ///< 0 = all cores
  AovSelection aov;
  bool stats = false;       ///< per-class counters (grid only), chosen once per frame
  std::uint64_t stats_max_bytes = std::uint64_t(1) << 32;  ///< budget for per-cell counters plus the grid
};

struct RenderResult {
  double seconds = 0;
  std::shared_ptr<const RenderCounters> counters;  ///< merged per-class counters when stats were on
  std::string stats_note;                          ///< why per-cell statistics were refused, if they were
  std::uint64_t rays = 0;            ///< every accelerator query (closest and any hit)
  std::uint64_t rejected_samples = 0;  ///< non-finite radiance samples, replaced by 0
};

/// Called after each finished tile with (tiles done, tiles in all); it must be
/// cheap and thread-safe.
using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

/// Renders `scene` through `accel` (built over scene.triangles) into `film`.
/// Pixels depend only on the scene, the settings' spp/max_depth/rr_depth/seed
/// and which exact accelerator answers: never on thread count or scheduling.
RenderResult render(const Scene& scene, const Accelerator& accel, const RenderSettings& settings, Film& film,
                    const ProgressCallback& progress = {});

}  // namespace kappa
