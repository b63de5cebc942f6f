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
  /// Per-cell counts for 1 path in this many (1 = every path; 0 = auto, see
  /// auto_cell_sample); per-class totals always count every ray.
  std::uint64_t cell_sample = 0;
};

/// Grids up to this many cells keep every path's per-cell counts by default.
inline constexpr std::uint64_t kFullCellCountLimit = std::uint64_t(1) << 16;
/// 1 path in this many is counted per cell by default on larger grids.
inline constexpr std::uint64_t kDefaultCellSample = 64;

/// --cell-sample auto: on a small grid the per-cell arrays stay in cache and
/// counting every path costs little; on a large one each cell a ray crosses
/// writes a line of memory, so 1 path in kDefaultCellSample is counted.
inline std::uint64_t auto_cell_sample(std::uint64_t cells) {
  return cells <= kFullCellCountLimit ? 1 : kDefaultCellSample;
}

/// Memory for per-cell statistics on a grid of `cells` cells rendered by
/// `threads` threads: per thread and class 32-bit visits and 64-bit tests and
/// hits; per class the 64-bit visits they fold into; while the report or the
/// cell map is made, Theta_i (32-bit) and two 64-bit arrays of visits.
inline std::uint64_t per_cell_stats_bytes(std::uint64_t cells, std::uint64_t threads) {
  return cells * ((4 + 8 + 8) * kRenderClasses * threads + 8 * kRenderClasses + 4 + 8 + 8);
}

struct RenderResult {
  double seconds = 0;
  std::shared_ptr<const RenderCounters> counters;  ///< merged per-class counters when stats were on
  std::string stats_note;                          ///< why per-cell statistics were refused, if they were
  std::uint64_t cell_sample = 1;                   ///< per-cell counts kept for 1 path in this many
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
