// The four-lane triangle test (accel/triangle4.h) gives, lane by lane, the
// scalar test's verdict and its t and barycentrics bit for bit, whatever the
// lane count, the ray's range (limits one ulp either side of a hit, where
// the range test before the division and t itself round differently), the
// scale, and at the zero edge functions the scalar test decides in double
// (rays through shared vertices and edges).
#include "accel/triangle4.h"

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

/// Checks every lane of one batch against the scalar test at `tmax`;
/// returns how many lanes were decided by the lanes (not flagged exact).
int expect_lanes_match(const Ray& ray, const Triangle* const batch[4], int count, float tmax) {
  const PreparedRay prepared(ray);
  Lanes4 lanes;
  intersect4(prepared, batch, count, ray.tmin, lanes);
  EXPECT_EQ(lanes.valid & ~((1 << count) - 1), 0) << "a masked lane is valid";
  EXPECT_EQ(lanes.valid & lanes.exact, 0);
  int decided = 0;
  for (int i = 0; i < count; ++i) {
    const Scalar s = scalar_test(prepared, *batch[i], ray.tmin, tmax);
    if (lanes.exact >> i & 1) continue;  // the walk runs the scalar test on it
    ++decided;
    const bool hit = (lanes.valid >> i & 1) && accept4(lanes, i, ray.tmin, tmax);
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

TEST(Triangle4, EveryLaneIsTheScalarTestOnRandomTrianglesAndRanges) {
  std::mt19937 rng(7);
  int hits = 0, decided = 0;
  for (const float scale : {1e-6f, 1.0f, 1e6f}) {
    std::uniform_real_distribution<float> u(-scale, scale);
    const auto point = [&] { return Vec3f{u(rng), u(rng), u(rng)}; };
    for (int trial = 0; trial < 20000; ++trial) {
      // Triangles near the ray, so that about half the lanes hit.
      Ray ray{point(), point()};
      if (ray.d == Vec3f{0, 0, 0}) continue;
      Triangle tris[4];
      const Triangle* batch[4];
      for (int i = 0; i < 4; ++i) {
        const Vec3f centre = ray.o + ray.d * (0.5f + float(i));
        std::uniform_real_distribution<float> near(-0.6f * scale, 0.6f * scale);
        const auto corner = [&] { return centre + Vec3f{near(rng), near(rng), near(rng)}; };
        tris[i] = Triangle{corner(), corner(), corner()};
        batch[i] = &tris[i];
      }
      const int count = 1 + trial % 4;
      decided += expect_lanes_match(ray, batch, count, ray.tmax);
      // Limits at each lane's own hit and one ulp either side of it.
      for (int i = 0; i < count; ++i) {
        const Scalar s = scalar_test(PreparedRay(ray), tris[i], ray.tmin, ray.tmax);
        if (!s.hit) continue;
        ++hits;
        for (const float limit : {s.t, std::nextafter(s.t, 0.0f), std::nextafter(s.t, INFINITY),
                                  closest_limit(Hit{0, s.t, 0, 0, 0})})
          expect_lanes_match(ray, batch, count, limit);
        ray.tmin = std::nextafter(s.t, 0.0f);  // and a tmin just below it
        expect_lanes_match(ray, batch, count, ray.tmax);
        ray.tmin = 0;
      }
    }
  }
  EXPECT_GT(hits, 10000);  // the ranges around a hit were exercised
  EXPECT_GT(decided, 100000);
}

TEST(Triangle4, ZeroEdgeFunctionsGoToTheScalarTestAndTheRestMatch) {
  // A fan of triangles around integer vertices, hit by axis-parallel and
  // diagonal rays through those vertices and along the shared edges: U, V or
  // W is exactly zero there.
  std::vector<Triangle> fan;
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
        for (std::size_t first = 0; first + 4 <= fan.size(); first += 4) {
          const Triangle* batch[4] = {&fan[first], &fan[first + 1], &fan[first + 2], &fan[first + 3]};
          Lanes4 lanes;
          intersect4(PreparedRay(ray), batch, 4, ray.tmin, lanes);
          exact += std::popcount(unsigned(lanes.exact));
          decided += expect_lanes_match(ray, batch, 4, ray.tmax);
        }
      }
  EXPECT_GT(exact, 100);  // the zero edge functions occurred
  EXPECT_GT(decided, 1000);
}

}  // namespace
}  // namespace kappa
