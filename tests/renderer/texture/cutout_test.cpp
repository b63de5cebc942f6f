// Cut-outs (renderer/texture/cutout_filter.h) in the visibility queries: a
// quad whose opacity map is a checkerboard lets exactly the rays through its
// transparent checks pass, closest and any hit, with naive, grid, grid2 and
// Embree agreeing (the exact three bitwise); a cut-out shadow caster blocks
// the fraction of a light its opaque checks cover.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "accel/factory.h"
#include "renderer/texture/cutout_filter.h"
#include "test_util.h"

namespace kappa {
namespace {

constexpr int kChecks = 8;  // the mask: 8 x 8 checks, opaque where x + y is even

/// A unit quad at z = 0 over [0, 1]^2 with (u, v) = (x, y), cut out by a
/// checkerboard mask, and a random soup behind it (z < -1.5) for the
/// accelerators' structure, opaque.
Scene checker_quad_scene() {
  Scene s;
  Material card;
  card.name = "card";
  card.maps[std::size_t(MapSlot::opacity)] = 0;
  s.materials.push_back(card);
  Material grey;
  grey.name = "grey";
  s.materials.push_back(grey);
  TextureMap map;
  map.slot = MapSlot::opacity;
  map.mask = 0;
  s.texture_maps.push_back(map);
  OpacityMask mask;
  mask.width = mask.height = kChecks;
  for (int y = 0; y < kChecks; ++y)
    for (int x = 0; x < kChecks; ++x) mask.opaque.push_back((x + y) % 2 == 0);
  s.opacity_masks.push_back(mask);
  s.triangles.push_back(Triangle{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
  s.triangles.push_back(Triangle{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  s.uvs.push_back(TriangleUVs{{{0, 0}, {1, 0}, {1, 1}}});
  s.uvs.push_back(TriangleUVs{{{0, 0}, {1, 1}, {0, 1}}});
  s.material_of = {0, 0};
  for (Triangle t : test::random_soup(400, 7, 0.15f)) {
    t.v0.z = t.v0.z * 0.2f - 2.0f, t.v1.z = t.v1.z * 0.2f - 2.0f, t.v2.z = t.v2.z * 0.2f - 2.0f;
    s.triangles.push_back(t);
    s.uvs.push_back(TriangleUVs{});
    s.material_of.push_back(1);
  }
  return s;
}

/// Whether the mask is transparent at (u, v), t = 1 - v naming the row.
bool transparent_at(float u, float v) {
  const int x = int(u * kChecks), y = int((1.0f - v) * kChecks);
  return (x + y) % 2 != 0;
}

bool same_hit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->triangle == b->triangle && std::bit_cast<std::uint32_t>(a->t) == std::bit_cast<std::uint32_t>(b->t) &&
         std::bit_cast<std::uint32_t>(a->b1) == std::bit_cast<std::uint32_t>(b->b1) &&
         std::bit_cast<std::uint32_t>(a->b2) == std::bit_cast<std::uint32_t>(b->b2);
}

TEST(Cutouts, ACheckerboardQuadLetsExactlyItsTransparentHalfThroughInEveryAccelerator) {
  const Scene scene = checker_quad_scene();
  const CutoutFilter filter(scene);
  ASSERT_TRUE(filter.any());
  ASSERT_TRUE(scene.has_cutouts());
  const FunctionHitFilter f = FunctionHitFilter::of(filter);
  AccelOptions options;
  options.filtered = true;
  const auto naive = make_accelerator("naive", scene.triangles, options);
  const auto grid = make_accelerator("grid", scene.triangles, options);
  const auto grid2 = make_accelerator("grid2", scene.triangles, options);
  const auto embree = make_accelerator("embree", scene.triangles, options);

  // Rays straight down through 64 x 64 points, each at the centre of a
  // sub-square of a check (so no ray grazes a check's edge), and rays at
  // random slants through random points.
  std::vector<Ray> rays;
  std::vector<bool> expect_through;
  const int n = 64;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float u = (float(i) + 0.5f) / float(n), v = (float(j) + 0.5f) / float(n);
      rays.push_back(Ray{{u, v, 1.0f}, {0, 0, -1}, 0.0f, 1.5f});
      expect_through.push_back(transparent_at(u, v));
    }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uni(0.02f, 0.98f), slant(-0.3f, 0.3f);
  for (int k = 0; k < 4000; ++k) {
    const float u = uni(rng), v = uni(rng);
    const Vec3f d = normalize(Vec3f{slant(rng), slant(rng), -1.0f});
    rays.push_back(Ray{Vec3f{u, v, 0.0f} - d * 2.0f, d});
    expect_through.push_back(transparent_at(u, v));
  }

  std::size_t through = 0, embree_disagrees = 0;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const std::optional<Hit> a = naive->closest_hit(rays[r], f);
    ASSERT_TRUE(same_hit(a, grid->closest_hit(rays[r], f))) << "grid, ray " << r;
    ASSERT_TRUE(same_hit(a, grid2->closest_hit(rays[r], f))) << "grid2, ray " << r;
    const bool quad_hit = a && a->triangle < 2;
    EXPECT_EQ(quad_hit, !expect_through[r]) << "ray " << r;
    if (r < std::size_t(n * n)) {
      // The straight rays end before the soup: any hit is the quad's.
      const bool occluded = naive->any_hit(rays[r], f);
      EXPECT_EQ(occluded, grid->any_hit(rays[r], f)) << r;
      EXPECT_EQ(occluded, grid2->any_hit(rays[r], f)) << r;
      EXPECT_EQ(occluded, embree->any_hit(rays[r], f)) << r;
      EXPECT_EQ(occluded, !expect_through[r]) << r;
      through += !occluded;
    }
    const std::optional<Hit> e = embree->closest_hit(rays[r], f);
    embree_disagrees += e.has_value() != a.has_value() || (a && e->triangle != a->triangle);
    // Without the filter the quad is solid.
    if (r < std::size_t(n * n)) EXPECT_TRUE(naive->any_hit(rays[r])) << r;
  }
  EXPECT_EQ(through, std::size_t(n * n / 2));
  EXPECT_EQ(embree_disagrees, 0u);
}

TEST(Cutouts, AConstantOpacityBelowAHalfHidesTheSurfaceAndAtAHalfKeepsIt) {
  Scene scene = checker_quad_scene();
  scene.materials[0].maps = kNoMaps;
  scene.materials[0].opacity = 0.49f;
  const Ray down{{0.3f, 0.6f, 1.0f}, {0, 0, -1}, 0.0f, 1.5f};
  {
    const CutoutFilter filter(scene);
    const auto naive = make_accelerator("naive", scene.triangles);
    EXPECT_FALSE(naive->any_hit(down, FunctionHitFilter::of(filter)));
  }
  scene.materials[0].opacity = 0.5f;
  const CutoutFilter opaque(scene);
  EXPECT_FALSE(opaque.any());
  EXPECT_FALSE(scene.has_cutouts());
}

TEST(Cutouts, EachLookupIsCountedAsAnAlphaTest) {
  const Scene scene = checker_quad_scene();
  const CutoutFilter filter(scene);
  std::uint64_t lookups = 0;
  filter.test(Hit{0, 1.0f, 0.5f, 0.25f, 0.25f}, lookups);
  filter.test(Hit{5, 1.0f, 0.5f, 0.25f, 0.25f}, lookups);  // a soup triangle: opaque, no lookup
  EXPECT_EQ(lookups, 1u);
}

/// A point under a cut-out card (half its checks opaque) sees a square
/// light above through it: the card blocks half of the light (the checks
/// are small against the light's image on the card).
TEST(Cutouts, ACutOutShadowCasterBlocksTheFractionItsOpaqueChecksCover) {
  const Scene scene = checker_quad_scene();
  const CutoutFilter filter(scene);
  AccelOptions options;
  options.filtered = true;
  const auto grid = make_accelerator("grid", scene.triangles, options);
  const auto embree = make_accelerator("embree", scene.triangles, options);
  const Vec3f p{0.5f, 0.5f, -1.0f};  // under the card's centre, above the soup
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const int n = 200000;
  int blocked = 0, embree_blocked = 0;
  for (int k = 0; k < n; ++k) {
    // The light: the square [0.25, 0.75]^2 at z = 1, twice as far as the card.
    const Vec3f q{0.25f + 0.5f * uni(rng), 0.25f + 0.5f * uni(rng), 1.0f};
    const Vec3f d = q - p;
    const float len = length(d);
    const Ray r{p, d / len, 0.0f, len};
    blocked += grid->any_hit(r, FunctionHitFilter::of(filter));
    embree_blocked += embree->any_hit(r, FunctionHitFilter::of(filter));
  }
  // The light's image on the card covers [0.375, 0.625]^2: 2 x 2 checks
  // of 1/8, half of them opaque.
  const double fraction = double(blocked) / n;
  EXPECT_NEAR(fraction, 0.5, 4.0 * std::sqrt(0.25 / n)) << fraction;
  EXPECT_NEAR(double(embree_blocked) / n, fraction, 1e-3);
}

}  // namespace
}  // namespace kappa
