// Which cells one tile's walks entered lately: the measure of coherence
// behind the coherent time model (stats/time_model.h). A cell step is
// "cold" when the cell is not among the last cells this table remembers: a
// direct-mapped table of 1,024 cells, about what the first-level cache holds
// of a walk's cell records and triangle lists. Neighbouring camera rays enter
// the same cells one after another, so few of their steps are cold; deep
// bounce rays and the rays of a triangle soup find most cells cold. A cold
// step waits for its cell's data and its triangles, which a warm one finds
// at hand: the cost eq 10 and the working-set terms do not see, and the one
// that made the extended model over-predict coherent rays on fine grids
// (issue 50's note gives the evidence).
//
// A table lives in one tile's queries and starts empty with each tile in
// each pass, so the counts depend on the tile's paths and the frame's passes
// alone, not on which thread walked which tile before: the same for any
// thread count or rank count. A frame cut into other passes (a checkpointed
// or resumed render, whose passes follow the clock) counts a few more cold
// steps at the passes' starts: its cold counts, like its occluder cache's,
// are those of its passes.
#pragma once

#include <array>
#include <cstdint>

namespace kappa {

class RecentCells {
 public:
  static constexpr int kSlotBits = 10;
  static constexpr std::size_t kSlots = std::size_t(1) << kSlotBits;

  /// Records a step into cell `c`; true if the step was cold (c was not in
  /// the table).
  bool visit(std::uint64_t c) {
    // Fibonacci hashing: neighbouring cells (consecutive indices) land in
    // different slots, as do a row's or a slab's apart, but for strides that
    // are multiples of 4,096 cells (tests/stats/recent_cells_test.cpp).
    const std::size_t slot = std::size_t((c * 0x9E3779B97F4A7C15ull) >> (64 - kSlotBits));
    const std::uint64_t tag = c + 1;  // 0 marks an empty slot
    const bool cold = m_tags[slot] != tag;
    m_tags[slot] = tag;
    return cold;
  }

 private:
  std::array<std::uint64_t, kSlots> m_tags{};
};

}  // namespace kappa
