// The clock that times every query: its rate agrees with steady_clock, its
// cap holds, and it reads /proc/cpuinfo's flags as words.
#include "stats/query_clock.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace kappa {
namespace {

/// Seconds the clock measures across a sleep, beside steady_clock's.
void expect_agrees_with_steady_clock(const QueryClock& clock) {
  const auto wall_start = std::chrono::steady_clock::now();
  const std::uint64_t start = clock.now();
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  const std::uint64_t end = clock.now();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  // Not through elapsed(): 60 ms is far past the per-query cap.
  const double measured = clock.seconds(end - start);
  EXPECT_NEAR(measured / wall, 1.0, 0.01) << clock.source() << ": " << measured << " s against " << wall << " s";
}

TEST(QueryClock, TheTscAndSteadyClockAgreeOnASleep) {
  expect_agrees_with_steady_clock(QueryClock(false));
  if (cpu_has_constant_tsc()) expect_agrees_with_steady_clock(QueryClock(true));
  EXPECT_STREQ(QueryClock(false).source(), "steady_clock");
}

TEST(QueryClock, AQueryPastTheCapCountsAsTheCapAndIsCounted) {
  for (bool tsc : {false, cpu_has_constant_tsc()}) {
    const QueryClock clock(tsc);
    bool capped = true;
    const std::uint64_t cap = std::uint64_t(QueryClock::kQueryCapSeconds * clock.ticks_per_second());
    const std::uint64_t short_query = clock.elapsed(1000, 1000 + cap / 2, capped);
    EXPECT_FALSE(capped);
    EXPECT_LE(short_query, cap / 2);
    const std::uint64_t long_query = clock.elapsed(1000, 1000 + 50 * cap, capped);
    EXPECT_TRUE(capped);
    EXPECT_NEAR(clock.seconds(long_query), QueryClock::kQueryCapSeconds, 1e-9);
    // An empty interval never goes negative after the clock's own cost.
    EXPECT_EQ(clock.elapsed(5, 5, capped), 0u);
    EXPECT_FALSE(capped);
    // An end before the start (counters of two CPUs apart) is no time, and
    // untrusted: not a wrapped-around 2^64.
    EXPECT_EQ(clock.elapsed(1000, 400, capped), 0u);
    EXPECT_TRUE(capped);
  }
}

TEST(QueryClock, ConstantTscIsAWholeWordOfAFlagsLine) {
  EXPECT_TRUE(cpu_has_constant_tsc("processor\t: 0\nflags\t\t: fpu tsc constant_tsc nonstop_tsc\n"));
  EXPECT_FALSE(cpu_has_constant_tsc("flags\t\t: fpu tsc nonconstant_tsc\n"));
  EXPECT_FALSE(cpu_has_constant_tsc("model name\t: constant_tsc machine\nflags\t\t: fpu tsc\n"));
  EXPECT_FALSE(cpu_has_constant_tsc(""));
}

}  // namespace
}  // namespace kappa
