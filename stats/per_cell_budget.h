// How per-cell statistics fit in --grid-max-bytes, for a render and a cast
// alike: every path counted into per-thread arrays when they fit beside the
// structure; else one set of arrays all threads share, counting a sample of
// the paths (or rays); per-cell statistics refused only when even that set
// does not fit. Per-class totals always count every ray.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>

#include "counters.h"

namespace kappa {

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

/// Bytes of per-cell statistics over `cells` cells: `copies` sets (one per
/// thread when every path is counted, one shared when paths are sampled) of
/// `classes` CellArrays, and, while the report or cell map is made, Theta_i
/// and two 64-bit arrays of visits (a class's, and all classes').
inline std::uint64_t per_cell_bytes(std::uint64_t cells, std::uint64_t classes, std::uint64_t copies) {
  return cells * (CellArrays::kBytesPerCell * classes * copies + sizeof(std::uint32_t) + 2 * sizeof(std::uint64_t));
}

/// How a frame or cast keeps per-cell counts.
struct PerCellPlan {
  PerCell mode = PerCell::no;  ///< own: per-thread arrays; shared: one set; no: totals only
  std::uint64_t every = 1;     ///< 1 path (or ray) in this many is counted per cell
  std::uint64_t bytes = 0;     ///< what the per-cell statistics take
  std::string note;            ///< for stats_note: why counting was sampled or refused; empty if as asked
};

/// The plan for `classes` ray classes over `cells` cells with `threads`
/// threads, 1 path in `every` asked for (1: every path), beside a structure
/// of `structure_bytes`, within `budget` bytes.
PerCellPlan plan_per_cell(std::uint64_t cells, std::uint64_t classes, std::uint64_t threads, std::uint64_t every,
                          std::uint64_t structure_bytes, std::uint64_t budget);

}  // namespace kappa
