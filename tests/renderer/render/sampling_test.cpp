// Random streams and sample warps.
#include "renderer/render/sampling.h"

#include <gtest/gtest.h>

#include <set>

namespace kappa {
namespace {

TEST(Sampling, StreamsDependOnlyOnSeedPixelAndSample) {
  Rng a(1, 2, 3), b(1, 2, 3);
  for (int i = 0; i < 100; ++i) ASSERT_EQ(a.next_u32(), b.next_u32());
  std::set<std::uint32_t> firsts;
  for (std::uint64_t seed : {0, 1})
    for (std::uint64_t pixel : {0, 1, 2})
      for (std::uint64_t sample : {0, 1, 2}) firsts.insert(Rng(seed, pixel, sample).next_u32());
  EXPECT_EQ(firsts.size(), 18u);
}

TEST(Sampling, UniformIsInTheHalfOpenUnitInterval) {
  Rng rng(5, 6, 7);
  double sum = 0;
  for (int i = 0; i < 100000; ++i) {
    const float u = rng.uniform();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);
}

TEST(Sampling, CosineHemisphereIsUnitAndHasMeanCosineTwoThirds) {
  Rng rng(1, 1, 1);
  double sum_cos = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const Vec3f w = sample_cosine_hemisphere(rng.uniform(), rng.uniform());
    ASSERT_NEAR(length(w), 1.0f, 1e-5f);
    ASSERT_GE(w.z, 0.0f);
    sum_cos += w.z;
  }
  EXPECT_NEAR(sum_cos / n, 2.0 / 3.0, 0.003);  // E[cos] under cos/pi
}

TEST(Sampling, TriangleSamplesAreUniform) {
  // Uniform over the triangle: each barycentric has density 2(1 - b), so
  // P(b < 1/2) = 3/4 and E[b^2] = 1/6, and the 4 sub-triangles of the
  // midpoint subdivision get a quarter of the samples each. (A sampler
  // returning (1/3, 1/3, 1/3) has the right mean and fails all of these.)
  Rng rng(2, 2, 2);
  double mean[3] = {0, 0, 0}, mean_sq[3] = {0, 0, 0};
  int below_half[3] = {0, 0, 0}, quarter[4] = {0, 0, 0, 0};
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    float b[3];
    sample_triangle(rng.uniform(), rng.uniform(), b[0], b[1], b[2]);
    ASSERT_GE(b[0], 0.0f);
    ASSERT_GE(b[1], 0.0f);
    ASSERT_GE(b[2], -1e-7f);
    ASSERT_NEAR(b[0] + b[1] + b[2], 1.0f, 1e-6f);
    for (int k = 0; k < 3; ++k) mean[k] += b[k], mean_sq[k] += double(b[k]) * b[k], below_half[k] += b[k] < 0.5f;
    // The corner sub-triangle k holds b_k > 1/2; the middle one none.
    ++quarter[b[0] > 0.5f ? 0 : b[1] > 0.5f ? 1 : b[2] > 0.5f ? 2 : 3];
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(mean[k] / n, 1.0 / 3.0, 0.003) << k;
    EXPECT_NEAR(mean_sq[k] / n, 1.0 / 6.0, 0.003) << k;
    EXPECT_NEAR(double(below_half[k]) / n, 0.75, 0.005) << k;
  }
  for (int q : quarter) EXPECT_NEAR(double(q) / n, 0.25, 0.005);
}

TEST(Sampling, FrameIsOrthonormal) {
  for (const Vec3f n : {Vec3f{0, 0, 1}, Vec3f{0, 0, -1}, normalize(Vec3f{1, 2, 3}), Vec3f{1, 0, 0}}) {
    const Frame f(n);
    EXPECT_NEAR(dot(f.s, f.t), 0.0f, 1e-6f);
    EXPECT_NEAR(dot(f.s, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(dot(f.t, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(length(f.s), 1.0f, 1e-6f);
    EXPECT_NEAR(length(f.t), 1.0f, 1e-6f);
    EXPECT_NEAR(length(f.n), 1.0f, 1e-6f);
    // Right-handed: s x t = n.
    EXPECT_NEAR(length(cross(f.s, f.t) - f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(length(f.to_world({0, 0, 1}) - n), 0.0f, 1e-6f);
  }
}

TEST(Sampling, PowerHeuristicWeightsSumToOne) {
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 3.0f) + power_heuristic(3.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(power_heuristic(2.0f, 2.0f), 0.5f);
  EXPECT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
}

}  // namespace
}  // namespace kappa
