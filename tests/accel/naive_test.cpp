// The naive accelerator: the oracle every other accelerator is compared with.
#include "accel/naive.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "accel/factory.h"
#include "core/input_error.h"
#include "test_util.h"

namespace kappa {
namespace {

std::vector<Ray> random_rays(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < n; ++i) rays.push_back(Ray{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}});
  return rays;
}

TEST(Naive, ClosestHitIsTheMinimumOverAllTriangles) {
  const auto tris = test::random_soup(500, 1, 0.2f);
  const NaiveAccelerator accel(tris);
  std::size_t hit_count = 0;
  for (const Ray& ray : random_rays(2000, 2)) {
    float best_t = INFINITY;
    TriangleId best_id = kNoTriangle;
    for (TriangleId i = 0; i < tris.size(); ++i) {
      float t, b0, b1, b2;
      if (intersect_triangle(PreparedRay(ray), tris[i], ray.tmin, ray.tmax, t, b0, b1, b2) && t < best_t) {
        best_t = t;
        best_id = i;
      }
    }
    const auto hit = accel.closest_hit(ray);
    ASSERT_EQ(hit.has_value(), best_id != kNoTriangle);
    if (hit) {
      ++hit_count;
      EXPECT_EQ(hit->triangle, best_id);
      EXPECT_EQ(hit->t, best_t);
      EXPECT_NEAR(hit->b0 + hit->b1 + hit->b2, 1.0f, 1e-5f);
    }
    EXPECT_EQ(accel.any_hit(ray), hit.has_value());
  }
  EXPECT_GT(hit_count, 200u);  // the soup is dense enough for the test to mean something
}

TEST(Naive, AnyHitRespectsTmax) {
  const std::vector<Triangle> tris = {{{-1, -1, 2}, {1, -1, 2}, {0, 1, 2}}};
  const NaiveAccelerator accel(tris);
  EXPECT_TRUE(accel.any_hit(Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, 2.0f}));
  EXPECT_FALSE(accel.any_hit(Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, 1.9f}));
}

TEST(Naive, EmptySceneNeverHits) {
  const NaiveAccelerator accel(std::span<const Triangle>{});
  EXPECT_FALSE(accel.closest_hit(Ray{{0, 0, 0}, {0, 0, 1}}));
  EXPECT_FALSE(accel.any_hit(Ray{{0, 0, 0}, {0, 0, 1}}));
}

TEST(Accelerator, FactoryKnowsNaiveAndRejectsUnknownNames) {
  const auto tris = test::random_soup(10, 5, 0.2f);
  EXPECT_EQ(make_accelerator("naive", tris)->name(), "naive");
  EXPECT_THROW(make_accelerator("bvh4", tris), InputError);
}

}  // namespace
}  // namespace kappa
