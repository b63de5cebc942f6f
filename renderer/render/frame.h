// What a frame is asked (RenderSettings) and what it gives back
// (RenderResult), apart from render() itself so that the frames of each
// query choice (render_counting.h, tile_loop.h) and the report share them.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "renderer/render/film.h"
#include "stats/per_cell_budget.h"
#include "stats/render_counters.h"

namespace kappa {

struct RenderSettings {
  int spp = 16;
  int max_depth = 32;       ///< bounces after the camera ray; 1 = direct lighting only
  int rr_depth = 3;         ///< Russian roulette from this many bounces on; < 0 disables it
  std::uint64_t seed = 0;
  AovSelection aov;
  bool stats = false;       ///< per-class counters (grid only), chosen once per frame
  std::uint64_t stats_max_bytes = std::uint64_t(1) << 32;  ///< budget for per-cell counters plus the grid
  /// Per-cell counts for 1 path in this many (1 = every path; 0 = auto, see
  /// auto_cell_sample); per-class totals always count every ray.
  std::uint64_t cell_sample = 0;
};

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

}  // namespace kappa
