#include "per_cell_budget.h"

#include "core/byte_size.h"

namespace kappa {

/// Counting every path into per-thread arrays that do not fit falls back to
/// one shared set counting at least 1 path in this many (as --cell-sample
/// auto does on large grids).
inline constexpr std::uint64_t kFallbackCellSample = kMinAutoCellSample;

PerCellPlan plan_per_cell(std::uint64_t cells, std::uint64_t classes, std::uint64_t threads, std::uint64_t every,
                          std::uint64_t structure_bytes, std::uint64_t budget) {
  const auto fits = [&](std::uint64_t bytes) { return structure_bytes <= budget && bytes <= budget - structure_bytes; };
  const auto over = [&](std::uint64_t bytes, const std::string& what) {
    return byte_size(bytes) + " of " + what + " and " + byte_size(structure_bytes) +
           " of accelerator would exceed --grid-max-bytes (" + byte_size(budget) + ")";
  };
  PerCellPlan plan;
  std::string why;
  if (every <= 1) {
    // Counting every path writes at every step: each thread gets arrays of its own.
    plan.bytes = per_cell_bytes(cells, classes, threads);
    if (fits(plan.bytes)) {
      plan.mode = PerCell::own;
      return plan;
    }
    why = over(plan.bytes, "per-thread counters for " + std::to_string(threads) + " threads");
    every = kFallbackCellSample;
  }
  // Sampled paths write rarely: one set of arrays for all threads.
  plan.bytes = per_cell_bytes(cells, classes, 1);
  if (fits(plan.bytes)) {
    plan.mode = PerCell::shared;
    plan.every = every;
    if (!why.empty())
      plan.note = why + "; one shared set counts 1 path in " + std::to_string(every) +
                  " per cell instead (per-class totals count every ray)";
    return plan;
  }
  plan = PerCellPlan{};
  plan.note = "per-cell statistics refused: " + over(per_cell_bytes(cells, classes, 1), "counters") +
              "; per-class totals only";
  return plan;
}

}  // namespace kappa
