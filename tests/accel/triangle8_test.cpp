// The eight-lane triangle test (accel/triangle8.h, AVX2) gives, lane by lane,
// the scalar test's verdict and its t and barycentrics bit for bit, whatever
// the lane count, the ray's range (limits one ulp either side of a hit), the
// scale, and at the zero edge functions the scalar test decides in double.
// Skipped, with a message, on a CPU without AVX2.
#include "accel/triangle8.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>

namespace kappa {
namespace {

struct Scalar {
  bool hit = false;
  float t = 0, b0 = 0, b1 = 0, b2 = 0;
};

Scalar scalar_test(const PreparedRay& prepared, const Triangle& tri, float tmin, float tmax) {
  Scalar s;
  s.hit = intersect_triangle(prepared, tri, tmin, tmax, s.t, s.b0, s.b1, s.b2);
  return s;
}

/// Checks every lane of one group against the scalar test at `tmax`;
/// returns how many lanes the lanes decided (not flagged exact).
int expect_lanes_match(const Ray& ray, const Triangle* const group[8], int count, float tmax) {
  const PreparedRay prepared(ray);
  Triangle8 packed;
  pack8(group, count, packed);
  Lanes8 lanes;
  intersect8(prepared, packed, count, ray.tmin, lanes);
  EXPECT_EQ(lanes.valid & ~((1 << count) - 1), 0) << "a masked lane is valid";
  EXPECT_EQ(lanes.valid & lanes.exact, 0);
  int decided = 0;
  for (int i = 0; i < count; ++i) {
    const Scalar s = scalar_test(prepared, *group[i], ray.tmin, tmax);
    if (lanes.exact >> i & 1) continue;  // a walk runs the scalar test on it
    ++decided;
    const bool hit = (lanes.valid >> i & 1) && accept8(lanes, i, ray.tmin, tmax);
    EXPECT_EQ(hit, s.hit) << "lane " << i << " of " << count << ", tmax " << tmax;
    if (hit && s.hit) {
      EXPECT_EQ(std::bit_cast<std::uint32_t>(lanes.t[i]), std::bit_cast<std::uint32_t>(s.t));
      EXPECT_EQ(std::bit_cast<std::uint32_t>(lanes.b[0][i]), std::bit_cast<std::uint32_t>(s.b0));
      EXPECT_EQ(std::bit_cast<std::uint32_t>(lanes.b[1][i]), std::bit_cast<std::uint32_t>(s.b1));
      EXPECT_EQ(std::bit_cast<std::uint32_t>(lanes.b[2][i]), std::bit_cast<std::uint32_t>(s.b2));
    }
  }
  return decided;
}

TEST(Triangle8, PackingPutsEachTrianglesCoordinatesInItsLaneAndRepeatsLaneZero) {
  Triangle tris[3];
  const Triangle* group[3];
  for (int i = 0; i < 3; ++i) {
    const float f = float(10 * i);
    tris[i] = Triangle{{f + 1, f + 2, f + 3}, {f + 4, f + 5, f + 6}, {f + 7, f + 8, f + 9}};
    group[i] = &tris[i];
  }
  Triangle8 p;
  pack8(group, 3, p);
  for (int k = 0; k < 9; ++k)
    for (int i = 0; i < 8; ++i) EXPECT_EQ(p.c[k][i], float(10 * (i < 3 ? i : 0) + k + 1)) << k << " " << i;
}

TEST(Triangle8, EveryLaneIsTheScalarTestOnRandomTrianglesAndRanges) {
  if (!avx2_available()) GTEST_SKIP() << "this CPU has no AVX2: intersect8 is never called here";
  std::mt19937 rng(11);
  int hits = 0, decided = 0;
  for (const float scale : {1e-6f, 1.0f, 1e6f}) {
    std::uniform_real_distribution<float> u(-scale, scale);
    const auto point = [&] { return Vec3f{u(rng), u(rng), u(rng)}; };
    for (int trial = 0; trial < 10000; ++trial) {
      Ray ray{point(), point()};
      if (ray.d == Vec3f{0, 0, 0}) continue;
      Triangle tris[8];
      const Triangle* group[8];
      for (int i = 0; i < 8; ++i) {
        const Vec3f centre = ray.o + ray.d * (0.5f + float(i));
        std::uniform_real_distribution<float> near(-0.6f * scale, 0.6f * scale);
        const auto corner = [&] { return centre + Vec3f{near(rng), near(rng), near(rng)}; };
        tris[i] = Triangle{corner(), corner(), corner()};
        group[i] = &tris[i];
      }
      const int count = 1 + trial % 8;
      decided += expect_lanes_match(ray, group, count, ray.tmax);
      for (int i = 0; i < count; ++i) {
        const Scalar s = scalar_test(PreparedRay(ray), tris[i], ray.tmin, ray.tmax);
        if (!s.hit) continue;
        ++hits;
        for (const float limit : {s.t, std::nextafter(s.t, 0.0f), std::nextafter(s.t, INFINITY),
                                  closest_limit(Hit{0, s.t, 0, 0, 0})})
          expect_lanes_match(ray, group, count, limit);
        ray.tmin = std::nextafter(s.t, 0.0f);  // and a tmin just below it
        expect_lanes_match(ray, group, count, ray.tmax);
        ray.tmin = 0;
      }
    }
  }
  EXPECT_GT(hits, 20000);  // the ranges around a hit were exercised
  EXPECT_GT(decided, 100000);
}

TEST(Triangle8, ZeroEdgeFunctionsGoToTheScalarTestAndTheRestMatch) {
  if (!avx2_available()) GTEST_SKIP() << "this CPU has no AVX2: intersect8 is never called here";
  std::vector<Triangle> fan;  // around integer vertices: U, V or W is exactly zero on rays through them
  for (int x = -2; x < 2; ++x)
    for (int y = -2; y < 2; ++y) {
      const Vec3f a{float(x), float(y), 3}, b{float(x + 1), float(y), 3}, c{float(x), float(y + 1), 3},
          d{float(x + 1), float(y + 1), 3};
      fan.push_back({a, b, d});
      fan.push_back({a, d, c});
    }
  int exact = 0, decided = 0;
  for (float ox = -2; ox <= 2; ox += 0.5f)
    for (float oy = -2; oy <= 2; oy += 0.5f)
      for (const Vec3f d : {Vec3f{0, 0, 1}, Vec3f{0, 0, -1}, Vec3f{0.25f, 0, 1}, Vec3f{0.5f, 0.5f, 1}}) {
        const Ray ray{{ox, oy, d.z > 0 ? 0.0f : 6.0f}, d};
        for (std::size_t first = 0; first + 8 <= fan.size(); first += 8) {
          const Triangle* group[8];
          for (int i = 0; i < 8; ++i) group[i] = &fan[first + std::size_t(i)];
          Triangle8 packed;
          pack8(group, 8, packed);
          Lanes8 lanes;
          intersect8(PreparedRay(ray), packed, 8, ray.tmin, lanes);
          exact += std::popcount(unsigned(lanes.exact));
          decided += expect_lanes_match(ray, group, 8, ray.tmax);
        }
      }
  EXPECT_GT(exact, 100);  // the zero edge functions occurred
  EXPECT_GT(decided, 1000);
}

}  // namespace
}  // namespace kappa
