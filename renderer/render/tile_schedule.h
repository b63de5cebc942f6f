// Which of a pass's tiles this process renders. Without a schedule a frame
// renders every tile; with one, in every pass, the tiles it hands out (kappa-mpi's ranks
// share a frame this way, issue 48). A pixel's samples depend only on (seed,
// pixel, sample index), and a tile's per-tile state (its occluder cache)
// begins and ends with the tile, so a tile renders the same pixels wherever
// and with whatever else it runs: what lets a frame be split by tiles and
// put together bitwise (tests/renderer/render/tile_schedule_test.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>

namespace kappa {

struct Film;
class FrameAccumulator;

/// A frame's tiles are squares of this many pixels a side (the last row and
/// column cut by the film's edges), numbered row by row.
inline constexpr int kTileSize = 16;

class TileSchedule {
 public:
  virtual ~TileSchedule() = default;
  /// Before each pass: the frame has `tiles` tiles.
  virtual void begin_pass(std::size_t tiles) = 0;
  /// The next tile this process renders in the pass, or nullopt once it has
  /// none left. Called from every render thread, until each gets nullopt.
  virtual std::optional<std::size_t> next_tile() = 0;
  /// After the pass's last tile here, whose pixels are in `film` and whose
  /// relMSE estimates are in `tile_estimates` (by tile), with this process's
  /// `counts` (rays, non-finite samples): a schedule shared by processes
  /// brings every tile's pixels and estimates into the writing process's
  /// film and the counts' sums into its `counts`. A progressive frame's
  /// film is resolved from its sums after the pass: `film` is null then,
  /// and share_pass_state follows.
  virtual void end_pass(Film* film, std::span<double> tile_estimates, std::span<std::uint64_t> counts) = 0;
  /// A progressive frame, whose every process keeps every pixel's running
  /// sums (`bytes` a pixel) so that each decides the next pass alike: after
  /// end_pass, the pixels of every tile rendered elsewhere in the pass, into
  /// this process's sums. `pack(pixel, out)` writes one pixel's `bytes`,
  /// `unpack(pixel, in)` reads them; `width` the frame's, for the tiles.
  virtual void share_pass_state(int /*width*/, int /*height*/, std::size_t /*bytes*/,
                                const std::function<void(std::size_t, std::byte*)>& /*pack*/,
                                const std::function<void(std::size_t, const std::byte*)>& /*unpack*/) {}
  /// The writing process's `value` (a per-frame choice it makes for all,
  /// such as the per-cell sample rate), on every process; called by all at
  /// the same point.
  virtual std::uint64_t writer_value(std::uint64_t value) { return value; }
  /// `values` summed over the processes into the writer's (the frame's
  /// statistics, 64-bit); called by all at the same point, with as many.
  virtual void sum_on_writer(std::span<std::uint64_t> /*values*/) {}
};

/// A progressive frame shared by processes: the pass's pixels rendered
/// elsewhere, their samples and AOV sums, into this process's `acc`
/// (frame_accumulator.cpp: out of the tile loop, whose body the compiler
/// inlines whole).
void share_pass_state(TileSchedule& schedule, FrameAccumulator& acc, int width, int height);

}  // namespace kappa
