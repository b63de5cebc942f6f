// The occluder cache (renderer/render/occluder_cache.h): one remembered
// triangle per light, tested before a shadow ray's walk. It cannot change an
// image (the answer is the walk's), and its counts add up with the shadow
// class's walks to the shadow rays a frame without it walks.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "accel/factory.h"
#include "renderer/render/integrator.h"
#include "renderer/render/occluder_cache.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/scene_loader.h"
#include "stats/render_counters.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(OccluderCache, RemembersTheLastOccluderPerKeyAndForgetsItWhenARayReachesTheLight) {
  OccluderCache cache;
  EXPECT_EQ(cache.occluder(light_key(0)), kNoTriangle);
  cache.remember(light_key(3), 17);
  EXPECT_EQ(cache.occluder(light_key(3)), 17u);
  EXPECT_EQ(cache.occluder(light_key(4)), kNoTriangle);
  cache.remember(light_key(3), 18);  // the last occluder replaces the one before
  EXPECT_EQ(cache.occluder(light_key(3)), 18u);
  cache.remember(light_key(3), kNoTriangle);  // a ray reached the light
  EXPECT_EQ(cache.occluder(light_key(3)), kNoTriangle);
  // More keys than slots: each key finds its own occluder or none, never another's.
  for (std::uint32_t k = 0; k < 4 * OccluderCache::kSlots; ++k) cache.remember(light_key(k), 1000 + k);
  int kept = 0;
  for (std::uint32_t k = 0; k < 4 * OccluderCache::kSlots; ++k) {
    const TriangleId t = cache.occluder(light_key(k));
    if (t != kNoTriangle) {
      EXPECT_EQ(t, 1000 + k);
      ++kept;
    }
  }
  EXPECT_GT(kept, int(OccluderCache::kSlots) / 2);  // the keys spread over the slots
  EXPECT_LE(kept, int(OccluderCache::kSlots));
}

TEST(OccluderCache, TheEnvironmentIsKeyedByThePartOfTheSkyARayGoesTo) {
  const std::size_t env = 7;
  const LightKey up = light_key(env, Vec3f{0.01f, 1, 0.02f});
  EXPECT_EQ(up, light_key(env, normalize(Vec3f{0.02f, 1, 0.03f})));  // a nearby direction
  EXPECT_NE(up, light_key(env, Vec3f{0, -1, 0}));
  EXPECT_NE(up, light_key(env, Vec3f{1, 0.1f, 0}));
  EXPECT_NE(up, light_key(env, Vec3f{0.9f, 1, 0}));  // the same face, another of its 16 parts
  EXPECT_NE(up, light_key(env));
  // 6 faces x 16 parts, every one reached by some direction.
  std::set<LightKey> keys;
  for (int i = 0; i < 20000; ++i) {
    const float a = float(i) * 0.618034f, b = float(i) * 0.7548777f;
    const float z = 2.0f * (b - std::floor(b)) - 1.0f, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 6.2831853f * (a - std::floor(a));
    keys.insert(light_key(env, Vec3f{r * std::cos(phi), r * std::sin(phi), z}));
  }
  EXPECT_EQ(keys.size(), 96u);
  for (LightKey k : keys) EXPECT_EQ(k & 0xFFFFFFFFu, env);
}

struct Frame {
  Film film;
  RenderResult result;
};

Frame render_with(const Scene& scene, const std::string& accel, bool cache, bool stats) {
  RenderSettings settings;
  settings.spp = 4;
  settings.occluder_cache = cache;
  settings.stats = stats;
  settings.cell_sample = 1;
  AccelOptions options;
  options.filtered = scene.has_cutouts();
  const auto a = make_accelerator(accel, scene.triangles, options);
  Frame f{Film(scene.width, scene.height, settings.aov), {}};
  f.result = render(scene, *a, settings, f.film);
  return f;
}

/// A box on a floor under a sky (the environment's shadow rays), or under
/// a point light and a directional one.
Scene box_on_a_floor(bool sky) {
  Scene s;
  s.materials.push_back(Material{"white", {0.7f, 0.7f, 0.7f}, {0, 0, 0}});
  test::add_box(s, {-2, -1, -2}, {2, 0, 2}, false, 0);
  test::add_box(s, {-0.5f, 0, -0.5f}, {0.5f, 0.8f, 0.5f}, false, 0);
  if (sky) {
    s.environment = {0.4f, 0.5f, 0.6f};
  } else {
    PunctualLight point;
    point.position = {0.2f, 2.0f, 0.3f};
    point.intensity = {8, 8, 8};
    PunctualLight sun;
    sun.type = PunctualLight::Type::directional;
    sun.direction = normalize(Vec3f{0.3f, -1.0f, 0.4f});
    sun.intensity = {1, 1, 1};
    s.punctual_lights = {point, sun};
  }
  s.camera = CameraSpec{{0, 1.2f, -4}, {0, 0.4f, 0}, {0, 1, 0}, 50.0f};
  s.width = s.height = 32;
  return s;
}

Scene small(const std::filesystem::path& file) {
  Warnings warnings;
  Scene s = load_scene(file, warnings);
  s.width = s.height = 32;
  return s;
}

// An environment, triangle lights (the Cornell box), cut-outs and triangle lights (the
// textured box), a point and a spot light (glTF): with and without the
// cache, with statistics on and off, grid and grid2 render naive's image
// bit for bit; with statistics on, the cache's hits plus the shadow class's
// walks are the shadow rays of the frame without it, and its hits lie among
// its tests.
TEST(OccluderCache, CannotChangeAnImageAndItsCountsAddUp) {
  const std::vector<std::pair<const char*, std::filesystem::path>> files = {
      {"cornell", test::assets_dir() / "cornell-box" / "scene.json"},
      {"textured box (cut-outs)", test::assets_dir() / "textured-box" / "scene.json"}};
  std::vector<std::pair<std::string, Scene>> scenes = {{"sky", box_on_a_floor(true)},
                                                       {"point and directional lights", box_on_a_floor(false)}};
  for (const auto& [label, file] : files) scenes.emplace_back(label, small(file));
  for (const auto& [label, scene] : scenes) {
    SCOPED_TRACE(label);
    const Frame reference = render_with(scene, "naive", false, false);
    for (const char* accel : {"grid", "grid2"}) {
      SCOPED_TRACE(accel);
      const Frame without = render_with(scene, accel, false, true);
      std::uint64_t hits_seen = 0;
      for (bool stats : {false, true}) {
        const Frame with = render_with(scene, accel, true, stats);
        EXPECT_TRUE(test::bitwise_equal(with.film.rgb, reference.film.rgb));
        EXPECT_TRUE(with.result.occluder_cache);
        EXPECT_EQ(with.result.rays, without.result.rays);  // the queries asked are the same
        if (!stats) continue;
        const RenderCounters& on = *with.result.counters;
        const RenderCounters& off = *without.result.counters;
        EXPECT_EQ(off.occluder_cache_tests, 0u);
        EXPECT_EQ(off.occluder_cache_hits, 0u);
        EXPECT_LE(on.occluder_cache_hits, on.occluder_cache_tests);
        EXPECT_EQ(on.classes[kShadow].totals.rays + on.occluder_cache_hits, off.classes[kShadow].totals.rays);
        // Walks that found an occluder, and rays the cache found occluded, are the occluded rays.
        EXPECT_EQ(on.classes[kShadow].totals.hits + on.occluder_cache_hits, off.classes[kShadow].totals.hits);
        hits_seen = on.occluder_cache_hits;
      }
      // Every scene here has shadows: the cache answers some of its rays.
      EXPECT_GT(hits_seen, 0u);
      EXPECT_TRUE(test::bitwise_equal(without.film.rgb, reference.film.rgb));
    }
  }
}

// Naive and Embree are asked through the interface, whose any-hit query
// does not say which triangle occluded: they walk every shadow ray.
TEST(OccluderCache, AppliesOnlyWhereTheWalkNamesItsOccluder) {
  const Scene scene = small(test::assets_dir() / "cornell-box" / "scene.json");
  for (const char* accel : {"naive", "embree"}) {
    const Frame f = render_with(scene, accel, true, true);
    EXPECT_FALSE(f.result.occluder_cache) << accel;
    EXPECT_EQ(f.result.counters->occluder_cache_tests, 0u) << accel;
  }
  EXPECT_TRUE(render_with(scene, "grid", true, false).result.occluder_cache);
  EXPECT_FALSE(render_with(scene, "grid", false, false).result.occluder_cache);
}

}  // namespace
}  // namespace kappa
