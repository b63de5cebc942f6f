// The counting walks of a choice (--grid-res model, --accel auto): the
// pilot's segments walked through a candidate structure, summed into one
// load per class with the frame's cold steps estimated (stats/recent_cells.h).
//
// Each run of one frame tile's segments is replayed in the pilot's order
// against a table of recent cells empty at the run's start, as the frame's
// tile walks its own. For the rays that go anywhere (shadow and bounce rays)
// the pilot's cold steps per ray are then close to the frame's: a cell they
// enter is warm when some recent ray of the tile entered it, and the
// pilot's neighbouring paths are about as scattered as the frame's (their
// cold tests less so: stats/README.md gives the measured gaps). Camera rays differ:
// in the frame a pixel's samples follow one another, so sample s + 1 finds
// the cells of sample s's camera ray, less those its path's other rays
// evicted, while the pilot's next camera ray is a pixel several frame
// pixels away. So each camera segment is walked twice: first where it is
// (the first sample of a pixel, after its neighbour's path), and again once
// its path's other segments were walked (the pixel's later samples). The
// frame's camera rays are 1/spp first samples: its cold counts blend the two.
// Without the second walk, the cold camera steps came out 1.5-2.8x the
// frame's at 16 spp on four shared scenes (issue 50's note). Not modelled:
// a large film's tiles get few pilot paths each (a 1920 x 1080 frame has
// 8,160 tiles for at most 16,384 pilot pixels), so their first walks are
// colder than the frame's; and a frame whose passes split a pixel's samples
// (budgets, checkpoints) finds fewer of them warm than the blend assumes.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>

#include <tbb/enumerable_thread_specific.h>

#include "accel/ray.h"
#include "accel/recorder.h"
#include "recent_cells.h"
#include "render_counters.h"
#include "time_model.h"

namespace kappa {

/// One query of the pilot: the ray, its class and the hit the frame's walk
/// would stop at (for a shadow ray its closest occluder: the any-hit walk
/// stops there or before, so its counts are an upper bound).
struct PilotSegment {
  Ray ray;
  float t_hit = 0;
  bool hit = false;
  RenderClass ray_class = kCamera;
  /// The frame's tile whose pixels the pilot's pixel stands for. A counting
  /// walk replays each tile's segments in the pilot's order against a table
  /// of recent cells empty at the tile's start, as the frame's tile walks
  /// its own (stats/recent_cells.h): its cold steps then depend on the
  /// pilot's paths alone, not on the threads.
  std::uint32_t tile = 0;
  std::uint32_t pixel = 0;  ///< the pilot's pixel, for the order within a tile
};

/// Calls `walk(begin, end)` once for each run of consecutive segments of
/// one tile, in parallel; `segments` grouped by tile (a pilot's are).
void for_each_tile_run(std::span<const PilotSegment> segments,
                       const std::function<void(std::size_t begin, std::size_t end)>& walk);

namespace detail {

struct ReplayClassSums {
  std::uint64_t rays = 0, hits = 0, cells = 0, occupied = 0, tests = 0, skips = 0, descents = 0;
  std::uint64_t cold_cells = 0, cold_tests = 0;
  /// Camera rays only: the cold steps and tests of their second walk.
  std::uint64_t repeat_cold_cells = 0, repeat_cold_tests = 0;
  void add(const ReplayClassSums& o) {
    rays += o.rays, hits += o.hits, cells += o.cells, occupied += o.occupied, tests += o.tests, skips += o.skips;
    descents += o.descents;
    cold_cells += o.cold_cells, cold_tests += o.cold_tests;
    repeat_cold_cells += o.repeat_cold_cells, repeat_cold_tests += o.repeat_cold_tests;
  }
};
using ReplaySums = std::array<ReplayClassSums, kRenderClasses>;

/// Counts one walk's cells and tests and, with a table of recent cells, its
/// cold ones (accel/recorder.h); a repeat walk counts only its cold ones,
/// into the repeat sums.
struct ReplayRecorder {
  RecentCells* recent;  ///< null: cold steps not counted
  ReplayClassSums& sums;
  bool repeat = false;
  bool cold = false;  ///< the step last entered was cold
  template <class BoxFn>
  void cell(std::uint64_t c, int, BoxFn&&) {
    if (!recent) return;
    cold = recent->visit(c);
    (repeat ? sums.repeat_cold_cells : sums.cold_cells) += cold;
  }
  void test() { (repeat ? sums.repeat_cold_tests : sums.cold_tests) += cold; }
  void hit() {}
  void finish(const WalkCounts& c, const WalkSegment&) {
    if (repeat) return;
    sums.cells += c.cells, sums.occupied += c.occupied, sums.tests += c.tests, sums.skips += c.skips;
    sums.descents += c.descents;
  }
};

}  // namespace detail

/// The loads of `segments` (a pilot's: grouped by frame tile) walked by
/// `walk(segment, recorder)`, which returns whether the walk hit, with the
/// working set `working_set_bytes` (of it, `list_bytes` the lists' and
/// triangles': QueryLoad::list_bytes) and the cold counts of a frame of
/// `frame_spp` samples per pixel; without `frame_spp` (a model with no cold
/// terms) no cold step is counted, nor any camera segment walked twice.
/// Integer sums: the same for any thread count.
template <class Walk>
std::array<QueryLoad, kRenderClasses> replay_segments(std::span<const PilotSegment> segments, const Walk& walk,
                                                      double working_set_bytes, double list_bytes,
                                                      std::optional<double> frame_spp) {
  tbb::enumerable_thread_specific<detail::ReplaySums> per_thread;
  for_each_tile_run(segments, [&](std::size_t begin, std::size_t end) {
    detail::ReplaySums& sums = per_thread.local();
    std::optional<RecentCells> recent;
    if (frame_spp) recent.emplace();
    RecentCells* table = recent ? &*recent : nullptr;
    std::optional<std::size_t> camera;  // the current path's camera segment, to walk again at its end
    const auto walk_camera_again = [&] {
      if (!camera) return;
      detail::ReplayRecorder again{table, sums[kCamera], true};
      walk(segments[*camera], again);
      camera.reset();
    };
    for (std::size_t i = begin; i < end; ++i) {
      const PilotSegment& s = segments[i];
      if (s.ray_class == kCamera) walk_camera_again();
      detail::ReplayRecorder recorder{table, sums[s.ray_class]};
      const bool hit = walk(s, recorder);
      ++sums[s.ray_class].rays;
      sums[s.ray_class].hits += hit;
      if (s.ray_class == kCamera && table) camera = i;
    }
    walk_camera_again();
  });
  detail::ReplaySums all{};
  per_thread.combine_each([&](const detail::ReplaySums& t) {
    for (std::size_t k = 0; k < kRenderClasses; ++k) all[k].add(t[k]);
  });
  const double first = 1.0 / std::max(1.0, frame_spp.value_or(1.0));
  std::array<QueryLoad, kRenderClasses> loads{};
  for (std::size_t k = 0; k < kRenderClasses; ++k) {
    const detail::ReplayClassSums& a = all[k];
    QueryLoad& l = loads[k];
    l = QueryLoad{RenderClass(k), double(a.rays), double(a.cells), double(a.occupied), double(a.tests),
                  double(a.skips), double(a.hits), working_set_bytes};
    l.list_bytes = list_bytes;
    l.descents = double(a.descents);
    if (k == kCamera) {
      l.cold_cells = first * double(a.cold_cells) + (1 - first) * double(a.repeat_cold_cells);
      l.cold_tests = first * double(a.cold_tests) + (1 - first) * double(a.repeat_cold_tests);
    } else {
      l.cold_cells = double(a.cold_cells);
      l.cold_tests = double(a.cold_tests);
    }
  }
  return loads;
}

}  // namespace kappa
