// Secondary rays leave surfaces without hitting them again, at any scale and
// far from the origin, with no scene-dependent epsilon.
#include "renderer/render/interaction.h"

#include <gtest/gtest.h>

#include <random>

#include "accel/naive.h"
#include "renderer/render/sampling.h"

namespace kappa {
namespace {

/// Rays spawned from random points of a random triangle, into the hemisphere
/// of either side, must never hit that triangle; returns the self-hits.
std::size_t self_hits(float scale, const Vec3f& offset, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), u01(0.0f, 1.0f);
  std::size_t bad = 0;
  for (int k = 0; k < 200; ++k) {
    const std::vector<Triangle> tri = {
        {offset + Vec3f{u(rng), u(rng), u(rng)} * scale, offset + Vec3f{u(rng), u(rng), u(rng)} * scale,
         offset + Vec3f{u(rng), u(rng), u(rng)} * scale}};
    if (!(double_area(tri[0]) > 0)) continue;
    const NaiveAccelerator accel(tri);
    for (int i = 0; i < 200; ++i) {
      float b0, b1, b2;
      sample_triangle(u01(rng), u01(rng), b0, b1, b2);
      const SurfacePoint sp = surface_point(tri[0], b0, b1, b2);
      Vec3f local = sample_cosine_hemisphere(u01(rng), u01(rng));
      local.z = std::max(local.z, 1e-3f);  // include grazing directions
      const Vec3f n = (i % 2) ? sp.n : -sp.n;
      const Vec3f w = normalize(Frame(n).to_world(local));
      if (accel.any_hit(Ray{offset_ray_origin(sp, w), w})) ++bad;
    }
  }
  return bad;
}

TEST(RayOffset, NoSelfIntersectionAcrossScales) {
  for (float scale : {1e-6f, 1e-3f, 1.0f, 1e3f, 1e6f}) {
    EXPECT_EQ(self_hits(scale, {0, 0, 0}, 1), 0u) << "scale " << scale;
  }
}

TEST(RayOffset, NoSelfIntersectionFarFromTheOrigin) {
  EXPECT_EQ(self_hits(1.0f, {1e6f, -1e6f, 1e6f}, 2), 0u);
  EXPECT_EQ(self_hits(1e-2f, {1e4f, 3e4f, -2e4f}, 3), 0u);
}

TEST(RayOffset, OffsetIsAFewUlpsNotASceneEpsilon) {
  // A tilted triangle near x = 1e6, where one float ulp is 0.0625.
  const Triangle tri{{1e6f, 0, 0}, {1e6f + 1, 0, 1}, {1e6f, 1, 0.5f}};
  const SurfacePoint sp = surface_point(tri, 0.2f, 0.3f, 0.5f);
  const Vec3f o = offset_ray_origin(sp, sp.n);
  const float moved = length(o - sp.p);
  EXPECT_GT(moved, 0.0f);
  EXPECT_LT(moved, 1.0f);
  // Near the origin the same triangle moves by a few ulps of 1.
  const Triangle near{{0, 0, 0}, {1, 0, 1}, {0, 1, 0.5f}};
  const SurfacePoint sn = surface_point(near, 0.2f, 0.3f, 0.5f);
  EXPECT_LT(length(offset_ray_origin(sn, sn.n) - sn.p), 1e-5f);
}

}  // namespace
}  // namespace kappa
