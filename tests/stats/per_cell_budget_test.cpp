// How per-cell statistics fit in --grid-max-bytes, for render and cast alike.
#include "stats/per_cell_budget.h"

#include <gtest/gtest.h>

namespace kappa {
namespace {

constexpr std::uint64_t kCells = 100000, kStructure = 1000000;

TEST(PerCellBudget, BytesComeFromTheCountersSizes) {
  // Per cell: a 32-bit word and its carry word per class and copy, then
  // Theta_i (32-bit) and two 64-bit visit arrays while the report is made.
  EXPECT_EQ(per_cell_bytes(10, 1, 1), 10u * (8 + 4 + 16));
  EXPECT_EQ(per_cell_bytes(10, 5, 2), 10u * (8 * 5 * 2 + 4 + 16));
}

TEST(PerCellBudget, EveryPathIntoPerThreadArraysWhenTheyFit) {
  const std::uint64_t need = per_cell_bytes(kCells, 5, 4);
  const PerCellPlan plan = plan_per_cell(kCells, 5, 4, 1, kStructure, kStructure + need);
  EXPECT_EQ(plan.mode, PerCell::own);
  EXPECT_EQ(plan.every, 1u);
  EXPECT_EQ(plan.bytes, need);
  EXPECT_EQ(plan.note, "");
}

TEST(PerCellBudget, OneSharedSampledSetWhenPerThreadArraysDoNotFit) {
  const std::uint64_t own = per_cell_bytes(kCells, 5, 4), shared = per_cell_bytes(kCells, 5, 1);
  ASSERT_LT(shared, own);
  const PerCellPlan plan = plan_per_cell(kCells, 5, 4, 1, kStructure, kStructure + own - 1);
  EXPECT_EQ(plan.mode, PerCell::shared);
  EXPECT_EQ(plan.every, 64u);
  EXPECT_EQ(plan.bytes, shared);
  EXPECT_NE(plan.note.find("1 path in 64"), std::string::npos) << plan.note;
  EXPECT_NE(plan.note.find("per-thread"), std::string::npos) << plan.note;
}

TEST(PerCellBudget, SampledPathsAskedForShareOneSetWithoutANote) {
  const PerCellPlan plan = plan_per_cell(kCells, 5, 4, 256, kStructure, kStructure + per_cell_bytes(kCells, 5, 1));
  EXPECT_EQ(plan.mode, PerCell::shared);
  EXPECT_EQ(plan.every, 256u);
  EXPECT_EQ(plan.note, "");
}

TEST(PerCellBudget, RefusedOnlyWhenEvenTheSharedSetDoesNotFit) {
  const std::uint64_t shared = per_cell_bytes(kCells, 5, 1);
  for (std::uint64_t every : {std::uint64_t(1), std::uint64_t(64)}) {
    const PerCellPlan plan = plan_per_cell(kCells, 5, 4, every, kStructure, kStructure + shared - 1);
    EXPECT_EQ(plan.mode, PerCell::no) << every;
    EXPECT_EQ(plan.every, 1u);
    EXPECT_NE(plan.note.find("refused"), std::string::npos) << plan.note;
  }
  // A structure alone over the budget refuses too (no unsigned wrap-around).
  EXPECT_EQ(plan_per_cell(kCells, 1, 1, 1, 5000, 4000).mode, PerCell::no);
}

}  // namespace
}  // namespace kappa
