// KAPPA_CHECK: a broken invariant prints the condition and both operands,
// then aborts; a kept one costs nothing but its test.
#include "core/check.h"

#include <gtest/gtest.h>

#include <string>

namespace kappa {
namespace {

int checked_twice(int a, int b) {
  KAPPA_CHECK_LT(a, b);
  KAPPA_CHECK(a >= 0);
  return a + b;
}

TEST(Check, KeptInvariantsPassThrough) {
  EXPECT_EQ(checked_twice(1, 2), 3);
  KAPPA_CHECK_EQ(std::string("cell"), std::string("cell"));
  KAPPA_DCHECK_LE(1, 1);
}

TEST(CheckDeathTest, AFailedComparisonPrintsBothOperandsAndAborts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const unsigned slot = 7, row_end = 5;
  EXPECT_DEATH(KAPPA_CHECK_LT(slot, row_end),
               "kappa: internal error: check failed at .*check_test.cpp:[0-9]+: slot < row_end with slot = 7, "
               "row_end = 5");
  EXPECT_DEATH(checked_twice(-3, 2), "check failed at .*: a >= 0");
  EXPECT_DEATH(KAPPA_UNREACHABLE(), "unreachable code reached");
}

TEST(CheckDeathTest, DchecksRunInDebugBuildsOnly) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
#if !defined(NDEBUG) || (defined(KAPPA_DCHECKS) && KAPPA_DCHECKS)
  EXPECT_DEATH(KAPPA_DCHECK_EQ(1, 2), "1 == 2 with 1 = 1, 2 = 2");
#else
  int evaluated = 0;
  KAPPA_DCHECK((++evaluated, false));  // compiled, never evaluated, in Release
  EXPECT_EQ(evaluated, 0);
#endif
}

}  // namespace
}  // namespace kappa
