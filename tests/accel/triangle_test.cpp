// The watertight ray/triangle test (accel/triangle.h).
#include "accel/triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "accel/naive.h"
#include "test_util.h"

namespace kappa {
namespace {

bool hits(const Ray& ray, const Triangle& tri, float& t, float& b0, float& b1, float& b2) {
  return intersect_triangle(PreparedRay(ray), tri, ray.tmin, ray.tmax, t, b0, b1, b2);
}

TEST(Triangle, AnalyticHit) {
  const Triangle tri{{-1, -1, 2}, {1, -1, 2}, {0, 1, 2}};
  float t, b0, b1, b2;
  ASSERT_TRUE(hits(Ray{{0, 0, 0}, {0, 0, 1}}, tri, t, b0, b1, b2));
  EXPECT_FLOAT_EQ(t, 2.0f);
  EXPECT_FLOAT_EQ(b0, 0.25f);
  EXPECT_FLOAT_EQ(b1, 0.25f);
  EXPECT_FLOAT_EQ(b2, 0.5f);
  // Unnormalized directions: t is in units of |d|.
  ASSERT_TRUE(hits(Ray{{0, 0, 0}, {0, 0, 4}}, tri, t, b0, b1, b2));
  EXPECT_FLOAT_EQ(t, 0.5f);
}

TEST(Triangle, BothSidesAreHit) {
  const Triangle tri{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  float t, b0, b1, b2;
  EXPECT_TRUE(hits(Ray{{0, 0, -1}, {0, 0, 1}}, tri, t, b0, b1, b2));
  EXPECT_TRUE(hits(Ray{{0, 0, 1}, {0, 0, -1}}, tri, t, b0, b1, b2));
}

TEST(Triangle, RangeIsHalfOpenAtTminClosedAtTmax) {
  const Triangle tri{{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  float t, b0, b1, b2;
  EXPECT_TRUE(hits(Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, 1.0f}, tri, t, b0, b1, b2));
  EXPECT_FALSE(hits(Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, std::nextafter(1.0f, 0.0f)}, tri, t, b0, b1, b2));
  EXPECT_FALSE(hits(Ray{{0, 0, 0}, {0, 0, 1}, 1.0f, 5.0f}, tri, t, b0, b1, b2));
  EXPECT_FALSE(hits(Ray{{0, 0, 2}, {0, 0, 1}}, tri, t, b0, b1, b2));  // behind the origin
}

TEST(Triangle, SignedZeroAndAxisParallelDirections) {
  const Triangle tri{{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  float t, b0, b1, b2;
  ASSERT_TRUE(hits(Ray{{0, 0, 0}, {-0.0f, 0.0f, 1}}, tri, t, b0, b1, b2));
  EXPECT_EQ(t, 1.0f);
  // Subnormal components on the minor axes: no division by them, no NaN.
  ASSERT_TRUE(hits(Ray{{0, 0, 0}, {1e-40f, -1e-41f, 1}}, tri, t, b0, b1, b2));
  EXPECT_EQ(t, 1.0f);
  const Triangle wall{{2, -1, -1}, {2, 1, -1}, {2, 0, 1}};
  ASSERT_TRUE(hits(Ray{{0, 0, 0}, {1, -0.0f, -0.0f}}, wall, t, b0, b1, b2));
  EXPECT_EQ(t, 2.0f);
  ASSERT_TRUE(hits(Ray{{4, 0, 0}, {-1, 0, 0}}, wall, t, b0, b1, b2));
  EXPECT_EQ(t, 2.0f);
}

TEST(Triangle, DegenerateAndInPlaneRaysNeverHit) {
  const Triangle collinear{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}};
  const Triangle repeated{{0, 0, 1}, {0, 0, 1}, {0, 1, 1}};
  const Triangle flat{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  float t, b0, b1, b2;
  EXPECT_FALSE(hits(Ray{{0.5f, 0, 0}, {0, 0, 1}}, collinear, t, b0, b1, b2));
  EXPECT_FALSE(hits(Ray{{0, 0.1f, 0}, {0, 0, 1}}, repeated, t, b0, b1, b2));
  EXPECT_FALSE(hits(Ray{{-5, 0, 0}, {1, 0, 0}}, flat, t, b0, b1, b2));  // grazes inside the plane
}

TEST(Triangle, EqualDistanceTiesGoToTheLowerId) {
  const Triangle tri{{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  const PreparedRay r(Ray{{0, 0, 0}, {0, 0, 1}});
  Hit forward;
  test_closest(r, tri, 3, 0.0f, forward);
  test_closest(r, tri, 7, 0.0f, forward);
  Hit backward;
  test_closest(r, tri, 7, 0.0f, backward);
  test_closest(r, tri, 3, 0.0f, backward);
  EXPECT_EQ(forward.triangle, 3u);
  EXPECT_EQ(backward.triangle, 3u);
  EXPECT_EQ(forward.t, backward.t);
}

/// A cube of side 2 around the origin, each face an n x n grid of quads whose
/// lattice vertices are jittered (shared vertices get the same jitter), so
/// edges and vertices run in every direction, not only along the axes.
Scene jittered_cube(int n, float jitter, std::uint64_t seed) {
  auto lattice = [&](int i, int j, int k) {
    std::uint64_t h = seed;
    for (int c : {i, j, k}) h = (h ^ std::uint64_t(c + 1000)) * 0x100000001B3ull;
    std::mt19937 rng(std::uint32_t(h ^ (h >> 32)));
    std::uniform_real_distribution<float> u(-jitter, jitter);
    auto coord = [&](int c) {
      const float base = -1.0f + 2.0f * float(c) / float(n);
      return (c == 0 || c == n) ? base : base + u(rng);  // keep the faces planar at the corners' planes
    };
    return Vec3f{coord(i), coord(j), coord(k)};
  };
  Scene s;
  auto quad = [&](Vec3f a, Vec3f b, Vec3f c, Vec3f d) {
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
    s.material_of.insert(s.material_of.end(), {0, 0});
  };
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int side : {0, n}) {
        quad(lattice(side, a, b), lattice(side, a + 1, b), lattice(side, a + 1, b + 1), lattice(side, a, b + 1));
        quad(lattice(a, side, b), lattice(a + 1, side, b), lattice(a + 1, side, b + 1), lattice(a, side, b + 1));
        quad(lattice(a, b, side), lattice(a + 1, b, side), lattice(a + 1, b + 1, side), lattice(a, b + 1, side));
      }
    }
  }
  return s;
}

/// Casts `count` rays from random points inside the mesh: a third aimed at
/// vertices, a third at points on edges, a third in random directions.
/// Returns how many escaped.
/// Möller-Trumbore with its usual epsilon-free edge tests: correct on average,
/// but not watertight. The watertight tests below show their rays find its leaks,
/// so a pass for intersect_triangle means something.
bool moller_trumbore_hits_any(const std::vector<Triangle>& tris, const Ray& ray) {
  for (const Triangle& tri : tris) {
    const Vec3f e1 = tri.v1 - tri.v0, e2 = tri.v2 - tri.v0;
    const Vec3f p = cross(ray.d, e2);
    const float det = dot(e1, p);
    if (det == 0.0f) continue;
    const float inv = 1.0f / det;
    const Vec3f s = ray.o - tri.v0;
    const float u = dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    const Vec3f q = cross(s, e1);
    const float v = dot(ray.d, q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    if (dot(e2, q) * inv > 0.0f) return true;
  }
  return false;
}

template <typename HitsAny>
std::size_t escaping_rays(const Scene& mesh, float inner_radius, std::size_t count, std::uint32_t seed,
                          HitsAny hits_any) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::size_t escaped = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3f o{u(rng) * inner_radius, u(rng) * inner_radius, u(rng) * inner_radius};
    const Triangle& tri = mesh.triangles[pick(rng)];
    const Vec3f corners[3] = {tri.v0, tri.v1, tri.v2};
    Vec3f target;
    switch (i % 3) {
      case 0: target = corners[i / 3 % 3]; break;
      case 1: {
        const float w = u01(rng);
        target = corners[0] * (1 - w) + corners[1] * w;
        break;
      }
      default: target = o + Vec3f{u(rng), u(rng), u(rng)}; break;
    }
    if (target == o) continue;
    if (!hits_any(Ray{o, target - o})) ++escaped;
  }
  return escaped;
}

std::size_t escaping_rays(const Scene& mesh, float inner_radius, std::size_t count, std::uint32_t seed) {
  const NaiveAccelerator accel(mesh.triangles);
  return escaping_rays(mesh, inner_radius, count, seed, [&](const Ray& r) { return accel.closest_hit(r).has_value(); });
}

TEST(Triangle, WatertightSphere) {
  Scene sphere;
  test::add_sphere(sphere, {0, 0, 0}, 1.0f, 12, 24, false, 0);  // origins within 0.87 of the centre
  EXPECT_EQ(escaping_rays(sphere, 0.5f, test::scaled(600000), 1), 0u);
}

TEST(Triangle, WatertightJitteredCube) {
  const Scene cube = jittered_cube(5, 0.08f, 42);
  EXPECT_EQ(escaping_rays(cube, 0.9f, test::scaled(600000), 2), 0u);
}

TEST(Triangle, TheWatertightRaySetCatchesALeakyTest) {
  Scene sphere;
  test::add_sphere(sphere, {0, 0, 0}, 1.0f, 12, 24, false, 0);
  const std::size_t leaks = escaping_rays(sphere, 0.5f, 60000, 1, [&](const Ray& r) {
    return moller_trumbore_hits_any(sphere.triangles, r);
  });
  EXPECT_GT(leaks, 0u);
}

TEST(Triangle, WatertightFarFromTheOrigin) {
  // The same sphere translated by 1e4: float spacing is coarse, edges still hold.
  Scene sphere;
  test::add_sphere(sphere, {1e4f, -2e4f, 5e3f}, 1.0f, 8, 16, false, 0);
  const NaiveAccelerator accel(sphere.triangles);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::size_t escaped = 0;
  for (int i = 0; i < 100000; ++i) {
    const Vec3f o = Vec3f{1e4f, -2e4f, 5e3f} + Vec3f{u(rng), u(rng), u(rng)} * 0.3f;
    const Triangle& tri = sphere.triangles[std::size_t(i) % sphere.triangles.size()];
    if (!accel.closest_hit(Ray{o, tri.v0 - o})) ++escaped;
  }
  EXPECT_EQ(escaped, 0u);
}

// The build evaluates a*b+c as a rounded product then a rounded sum, never
// as one fused operation: with a = b = 1 + 2^-12, a*b = 1 + 2^-11 + 2^-24
// rounds to 1 + 2^-11 in float, so adding c = -(1 + 2^-11) gives 0, while an
// FMA keeps the 2^-24. (-ffp-contract=off; cmake/float_flags.cmake refuses
// flags that would change this.)
TEST(FloatFlags, MultiplyAddIsNotFused) {
  volatile float a = 1.0f + 0x1p-12f, b = 1.0f + 0x1p-12f, c = -(1.0f + 0x1p-11f);
  const float unfused = a * b + c;
  EXPECT_EQ(unfused, 0.0f);
  EXPECT_EQ(std::fma(float(a), float(b), float(c)), 0x1p-24f);  // the two do differ
}

}  // namespace
}  // namespace kappa
