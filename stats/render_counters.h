// The ray classes of a path-traced frame and their counters.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "counters.h"

namespace kappa {

/// camera, shadow (next-event estimation), bounce1, bounce2, bounce3+.
inline constexpr std::size_t kRenderClasses = 5;
inline constexpr std::array<const char*, kRenderClasses> kRenderClassNames = {"camera", "shadow", "bounce1", "bounce2",
                                                                              "bounce3+"};
enum RenderClass : std::size_t { kCamera = 0, kShadow = 1, kBounce1 = 2, kBounce2 = 3, kBounce3Plus = 4 };

/// The class of a closest-hit query at path depth `depth` (0 = camera ray).
inline RenderClass class_of_depth(int depth) {
  return depth == 0 ? kCamera : depth == 1 ? kBounce1 : depth == 2 ? kBounce2 : kBounce3Plus;
}

/// Per-cell arrays of each class, shared by every thread's counters.
using SharedCellArrays = std::array<std::shared_ptr<CellArrays>, kRenderClasses>;

/// Per-cell arrays for every class of a grid of `cells` cells, to share.
inline SharedCellArrays make_shared_cell_arrays(std::size_t cells) {
  SharedCellArrays a;
  for (auto& p : a) p = std::make_shared<CellArrays>(cells);
  return a;
}

/// One thread's counters for a frame.
struct RenderCounters {
  /// Per-cell arrays of this thread's own over `cells` cells of size
  /// `cell_size` (or totals only, if `per_cell` is false).
  RenderCounters(std::uint64_t cells, const Vec3d& cell_size, bool per_cell)
      : classes{CellCounters(cells, cell_size, per_cell), CellCounters(cells, cell_size, per_cell),
                CellCounters(cells, cell_size, per_cell), CellCounters(cells, cell_size, per_cell),
                CellCounters(cells, cell_size, per_cell)} {}
  /// Per-cell counts into `shared`, with every other thread.
  RenderCounters(const SharedCellArrays& shared, const Vec3d& cell_size)
      : classes{CellCounters(shared[0], cell_size), CellCounters(shared[1], cell_size),
                CellCounters(shared[2], cell_size), CellCounters(shared[3], cell_size),
                CellCounters(shared[4], cell_size)} {}
  /// Totals only, for an accelerator without cells.
  RenderCounters() : RenderCounters(0, Vec3d{}, false) {}

  std::array<CellCounters, kRenderClasses> classes;
  /// Traversal time of every query of a class, in QueryClock ticks (each
  /// query capped), and how many queries were capped.
  std::array<std::uint64_t, kRenderClasses> ticks{};
  std::array<std::uint64_t, kRenderClasses> capped{};

  void merge(const RenderCounters& o) {
    for (std::size_t k = 0; k < kRenderClasses; ++k) {
      classes[k].merge(o.classes[k]);
      ticks[k] += o.ticks[k];
      capped[k] += o.capped[k];
    }
  }
};

}  // namespace kappa
