// What a frame is asked (RenderSettings) and what it gives back
// (RenderResult), apart from render() itself so that the frames of each
// query choice (render_counting.h, tile_loop.h) and the report share them.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "renderer/render/film.h"
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

/// Grids up to this many cells keep every path's per-cell counts by default.
inline constexpr std::uint64_t kFullCellCountLimit = std::uint64_t(1) << 16;
/// On larger grids, about 1 path in N_c / kCellsPerSampledPath is counted,
/// but at least 1 in kMinAutoCellSample and never fewer than 1 in
/// kMaxAutoCellSample.
inline constexpr std::uint64_t kCellsPerSampledPath = 8192;
inline constexpr std::uint64_t kMinAutoCellSample = 64;
inline constexpr std::uint64_t kMaxAutoCellSample = 1024;

/// --cell-sample auto. On a small grid the per-cell arrays stay in cache and
/// counting every path costs little. On a larger one each counted cell is an
/// atomic increment into arrays the threads share (1 in 8 paths on 118 k
/// cells cost 13 %, 1 in 64 cost 5 %), and on millions of cells a cache miss
/// as well, so the rate falls as N_c grows: 1 path in N_c / 8192 rounded
/// down to a power of two, within [64, 1024] (Sponza's 2.1 M cells: 1 in
/// 256). stats/README.md gives what it costs and how near the estimates are.
inline std::uint64_t auto_cell_sample(std::uint64_t cells) {
  if (cells <= kFullCellCountLimit) return 1;
  return std::clamp(std::bit_floor(cells / kCellsPerSampledPath), kMinAutoCellSample, kMaxAutoCellSample);
}

/// Memory for per-cell statistics on a grid of `cells` cells with `copies`
/// sets of per-cell arrays (one per thread when every path is counted, one
/// shared when paths are sampled): per set and class 64-bit visits, tests and
/// hits; while the report or the cell map is made, Theta_i (32-bit) and two
/// 64-bit arrays of visits.
inline std::uint64_t per_cell_stats_bytes(std::uint64_t cells, std::uint64_t copies) {
  return cells * ((8 + 8 + 8) * kRenderClasses * copies + 4 + 8 + 8);
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

}  // namespace kappa
