// The machine probe (stats/machine_probe.h): the same queries every call, so
// that its time is the machine's speed and nothing else.
#include <gtest/gtest.h>

#include "stats/machine_probe.h"

namespace kappa {
namespace {

TEST(MachineProbe, CastsTheSameQueriesEveryCall) {
  const ProbeResult first = machine_probe(), second = machine_probe();
  // Some rays hit and some miss: both the walk and the tests take part.
  EXPECT_GT(first.hits, 0u);
  EXPECT_LT(first.hits, 4096u);
  EXPECT_EQ(first.hits, second.hits);
  EXPECT_GT(first.seconds, 0.0);
  EXPECT_GT(second.seconds, 0.0);
}

}  // namespace
}  // namespace kappa
