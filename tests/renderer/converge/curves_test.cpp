// What kappa converge computes: an image's error against a reference, and a
// curve's relMSE at a given time.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/converge/curves.h"
#include "renderer/converge/image_error.h"

namespace kappa {
namespace {

TEST(ImageError, RelmseRmseAndBiasOfAKnownDifference) {
  // Two pixels: the reference (1, 1, 1) and (0, 0, 0); the image 10 % above
  // it in the first and 0.1 in every channel of the second.
  const std::vector<float> ref = {1, 1, 1, 0, 0, 0};
  const std::vector<float> x = {1.1f, 1.1f, 1.1f, 0.1f, 0.1f, 0.1f};
  const ImageError e = image_error(x, ref);
  const double d = double(1.1f) - 1.0, z = double(0.1f);
  EXPECT_NEAR(e.relmse, (3 * d * d / 1.01 + 3 * z * z / 0.01) / 6, 1e-12);
  EXPECT_NEAR(e.rmse, std::sqrt((3 * d * d + 3 * z * z) / 6), 1e-12);
  EXPECT_NEAR(e.bias, (3 * double(1.1f) + 3 * z) / 3 - 1, 1e-12);
  EXPECT_EQ(image_error(ref, ref).relmse, 0.0);
  EXPECT_THROW(image_error(x, {1, 1, 1}), std::invalid_argument);
}

TEST(ImageError, TheReferenceFloorIsItsVarianceOverRefSquaredPlusEpsilon) {
  EXPECT_NEAR(relmse_floor({0.01f, 0.01f, 0.01f}, {1, 1, 1}), double(0.01f) / 1.01, 1e-12);
}

ConvergePoint point(int spp, double t, double relmse) {
  ConvergePoint p;
  p.spp = spp;
  p.time_s = t;
  p.error.relmse = relmse;
  return p;
}

TEST(Curves, RelmseAtATimeIsLogLogInterpolatedAndExtrapolatedAsOneOverTime) {
  // relMSE = 0.1 / t exactly: any log-log interpolation reproduces it.
  const std::vector<ConvergePoint> curve = {point(1, 1, 0.1), point(4, 4, 0.025), point(16, 16, 0.00625)};
  bool extrapolated = true;
  EXPECT_NEAR(relmse_at_time(curve, 2, &extrapolated), 0.05, 1e-15);
  EXPECT_FALSE(extrapolated);
  EXPECT_NEAR(relmse_at_time(curve, 16, &extrapolated), 0.00625, 1e-15);
  EXPECT_FALSE(extrapolated);
  EXPECT_NEAR(relmse_at_time(curve, 0.5, &extrapolated), 0.2, 1e-15);
  EXPECT_TRUE(extrapolated);
  EXPECT_NEAR(relmse_at_time(curve, 32, &extrapolated), 0.003125, 1e-15);
  EXPECT_TRUE(extrapolated);
  // A curve falling faster than 1/t between two points keeps its own slope there.
  const std::vector<ConvergePoint> steep = {point(1, 1, 1.0), point(2, 10, 0.01)};
  EXPECT_NEAR(relmse_at_time(steep, std::sqrt(10.0)), 0.1, 1e-12);
  // Points out of time order (each its own render) are read in time order.
  const std::vector<ConvergePoint> shuffled = {point(4, 4, 0.025), point(1, 1, 0.1), point(16, 16, 0.00625)};
  EXPECT_NEAR(relmse_at_time(shuffled, 2), 0.05, 1e-15);
}

TEST(Curves, EqualTimeIsTheShortestLastTime) {
  ConvergeCurve a{"a", "", "", "", {point(1, 1, 1), point(2, 3, 1)}};
  ConvergeCurve b{"b", "", "", "", {point(1, 0.5, 1), point(2, 2.5, 1)}};
  EXPECT_EQ(equal_time({a, b}), 2.5);
  ConvergeCurve c{"c", "", "", "", {point(1, 2, 1), point(2, 1.5, 1)}};  // its longest time first
  EXPECT_EQ(equal_time({a, c}), 2.0);
  EXPECT_EQ(equal_time({}), 0.0);
}

}  // namespace
}  // namespace kappa
