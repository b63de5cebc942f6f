// The built-in cost-model constants (used without a calibration file) are a
// whole calibration of the current format that predicts positive times.
#include "stats/builtin_calibration.h"

#include <gtest/gtest.h>

namespace kappa {
namespace {

TEST(BuiltinCalibration, IsAWholeCalibrationThatPredictsPositiveTimes) {
  const Calibration& c = builtin_calibration();
  EXPECT_GT(c.samples, 10u);
  EXPECT_FALSE(c.machine.empty());
  ASSERT_EQ(c.eq10.ns.size(), 3u);
  for (double ns : c.eq10.ns) EXPECT_GT(ns, 0.0);  // T0, Ts, Th: eq 10 needs all three
  ASSERT_EQ(c.extended.ns.size(), extended_model(1).ns.size());
  EXPECT_GT(c.extended.cache_bytes, 0.0);
  // A ray of 10 cells and 3 tests costs more than one of 1 cell and 1 test, in both models.
  const auto load = [](double cells, double tests) {
    return QueryLoad{kBounce1, 1000, 1000 * cells, 500 * cells, 1000 * tests, 0, 500, 1e6};
  };
  for (const TimeModel* m : {&c.eq10, &c.extended}) {
    EXPECT_GT(m->seconds(load(1, 1)), 0.0) << m->name;
    EXPECT_GT(m->seconds(load(10, 3)), m->seconds(load(1, 1))) << m->name;
  }
}

}  // namespace
}  // namespace kappa
