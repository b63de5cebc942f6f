// The per-cell counters' carry into the high words, and the zeroed arrays
// they are made of.
#include <gtest/gtest.h>

#include <thread>

#include "stats/split_counts.h"

namespace kappa {
namespace {

TEST(SplitCounts, IncrementCarriesPast32Bits) {
  SplitCounts c(3);
  EXPECT_EQ(c.at(0), 0u);
  c.add(1, 0xFFFFFFFEull);
  c.increment(1);
  EXPECT_EQ(c.at(1), 0xFFFFFFFFull);
  c.increment(1);
  EXPECT_EQ(c.at(1), 0x100000000ull);
  c.add(1, 0x500000003ull);
  EXPECT_EQ(c.at(1), 0x600000003ull);
  EXPECT_EQ(c.all(), (std::vector<std::uint64_t>{0, 0x600000003ull, 0}));
}

TEST(SplitCounts, SharedIncrementsFromThreadsCarryPast32Bits) {
  SplitCounts c(2);
  c.add(0, 0xFFFFFFFFull - 5000);
  const auto bump = [&] {
    for (int i = 0; i < 10000; ++i) c.increment_shared(i % 2);
  };
  std::thread a(bump), b(bump);
  a.join();
  b.join();
  EXPECT_EQ(c.at(0), 0xFFFFFFFFull - 5000 + 10000);
  EXPECT_EQ(c.at(1), 10000u);
}

TEST(ZeroedArray, StartsZeroAndAMovedFromArrayIsEmpty) {
  ZeroedArray<std::uint32_t> a(1 << 20);
  for (std::size_t i = 0; i < a.size(); i += 4099) EXPECT_EQ(a[i], 0u);
  a[7] = 5;
  ZeroedArray<std::uint32_t> copy(a);
  EXPECT_EQ(copy[7], 5u);
  ZeroedArray<std::uint32_t> moved(std::move(a));
  EXPECT_EQ(moved.size(), std::size_t(1) << 20);
  EXPECT_EQ(moved[7], 5u);
  EXPECT_TRUE(a.empty());  // NOLINT(bugprone-use-after-move): the moved-from state is what is tested
  // Under 2 MiB from calloc, from 2 MiB on mapped for huge pages: both start zero and copy alike.
  for (const std::size_t n : {std::size_t(1000), (std::size_t(2) << 20) / 8 - 1, (std::size_t(2) << 20) / 8 + 1}) {
    ZeroedArray<std::uint64_t> b(n);
    EXPECT_EQ(b[0], 0u);
    EXPECT_EQ(b[n - 1], 0u);
    b[n - 1] = 9;
    EXPECT_EQ(ZeroedArray<std::uint64_t>(b)[n - 1], 9u) << n;
  }
}

}  // namespace
}  // namespace kappa
