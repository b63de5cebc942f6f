// The cells of a cell-based accelerator, as statistics, reports and cell maps
// see them: N_c cells indexed 0 .. N_c - 1 (the indices the recorder
// protocol reports, accel/recorder.h), each with its occupancy Theta_i, its
// box and its level, so that leaves of different sizes and levels can be
// expressed. Read once per frame or report, never per ray.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"
#include "recorder.h"

namespace kappa {

class CellLayout {
 public:
  virtual ~CellLayout() = default;

  /// N_c: the cells rays visit and statistics count.
  virtual std::uint64_t cell_count() const = 0;
  /// Theta_i of every cell, in index order.
  virtual std::vector<std::uint32_t> occupancies() const = 0;
  /// Cell i's box and level (0 = the top, or the only, level).
  virtual CellBox cell_box(std::uint64_t i) const = 0;
  virtual int cell_level(std::uint64_t i) const = 0;
  /// The box the cells tile.
  virtual CellBox bounds() const = 0;
  /// The size every cell has when all have one (a uniform grid): what the
  /// model's eqs 19, 21, 22 and 24 take; nullopt when cells differ.
  virtual std::optional<Vec3d> uniform_cell_size() const = 0;
  /// Per level, its cells and their total occupancy, for a structure of
  /// more than one level (grid2); empty for one level, whose sizes are
  /// cell_count() and the sum of occupancies().
  struct Level {
    int level = 0;
    std::uint64_t N_c = 0;
    std::uint64_t theta_tot = 0;
  };
  virtual std::vector<Level> levels() const { return {}; }
  /// A short description of the structure ("64x32x16"), for metadata and summaries.
  virtual std::string resolution_text() const = 0;
};

}  // namespace kappa
