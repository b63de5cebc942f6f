// Pixels depend on (seed, pixel, sample index) only: never on thread count.
#include <gtest/gtest.h>

#include <cstring>

#include "accel/factory.h"
#include "core/thread_limit.h"
#include "renderer/render/camera.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

TEST(Determinism, CornellBoxIsBitwiseIdenticalAt1And2And4Threads) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  scene.width = scene.height = 48;
  RenderSettings settings;
  settings.spp = 8;
  settings.seed = 7;
  settings.aov = AovSelection{true, true, true};
  const auto render_on = [&](int threads) {
    const ThreadLimit limit(threads);
    return test::render_scene(scene, settings);
  };
  const Film one = render_on(1);
  for (int threads : {2, 4}) {
    const Film many = render_on(threads);
    EXPECT_TRUE(test::bitwise_equal(one.rgb, many.rgb)) << threads << " threads";
    EXPECT_TRUE(test::bitwise_equal(one.albedo, many.albedo)) << threads << " threads";
    EXPECT_TRUE(test::bitwise_equal(one.normal, many.normal)) << threads << " threads";
    EXPECT_TRUE(test::bitwise_equal(one.depth, many.depth)) << threads << " threads";
  }
  // The seed does matter: a different one gives a different image.
  settings.seed = 8;
  EXPECT_FALSE(test::bitwise_equal(one.rgb, test::render_scene(scene, settings).rgb));
}

TEST(Determinism, ImageIsFiniteAndLitWhereTheLightIs) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  EXPECT_TRUE(warnings.empty());
  scene.width = scene.height = 48;
  RenderSettings settings;
  settings.spp = 4;
  const Film film = test::render_scene(scene, settings);
  for (float v : film.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
  // Where the camera sees the ceiling light (its pixel centres' rays hit an
  // emissive triangle), the image holds at least the light's own radiance;
  // elsewhere, only what surfaces reflect, far less.
  const Camera camera(scene.camera, scene.width, scene.height);
  const auto naive = make_accelerator("naive", scene.triangles);
  double lit_sum = 0, dark_sum = 0;
  int lit = 0, dark = 0;
  for (int y = 0; y < scene.height; ++y) {
    for (int x = 0; x < scene.width; ++x) {
      const auto hit = naive->closest_hit(camera.generate_ray(float(x) + 0.5f, float(y) + 0.5f));
      const std::size_t p = std::size_t(y) * std::size_t(scene.width) + std::size_t(x);
      const double luminance = (film.rgb[3 * p] + film.rgb[3 * p + 1] + film.rgb[3 * p + 2]) / 3.0;
      if (hit && scene.materials[scene.material_of[hit->triangle]].emissive()) {
        const Vec3f Le = scene.materials[scene.material_of[hit->triangle]].emission;
        // Pixels on the light's edge mix in its dark surround: keep the inside.
        if (luminance > 0.5 * (Le.x + Le.y + Le.z) / 3.0) ++lit, lit_sum += luminance;
      } else if (hit) {
        ++dark, dark_sum += luminance;
      }
    }
  }
  ASSERT_GE(lit, 4) << "the light is in view";
  ASSERT_GT(dark, 1000);
  EXPECT_GT(lit_sum / lit, 10.0 * dark_sum / dark);
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

/// Every exact accelerator renders bitwise naive's image (and AOVs).
void expect_same_image_with_grid_and_naive(const std::filesystem::path& scene_file, int size, int spp) {
  Warnings warnings;
  Scene scene = load_scene(scene_file, warnings);
  scene.width = scene.height = size;
  RenderSettings settings;
  settings.spp = spp;
  settings.aov = AovSelection{true, true, true};
  const Film naive = test::render_scene(scene, settings, "naive");
  for (const char* exact : {"grid", "grid2"}) {
    const Film grid = test::render_scene(scene, settings, exact);
    EXPECT_TRUE(test::bitwise_equal(naive.rgb, grid.rgb)) << scene_file << " " << exact;
    EXPECT_TRUE(test::bitwise_equal(naive.albedo, grid.albedo)) << scene_file << " " << exact;
    EXPECT_TRUE(test::bitwise_equal(naive.normal, grid.normal)) << scene_file << " " << exact;
    EXPECT_TRUE(test::bitwise_equal(naive.depth, grid.depth)) << scene_file << " " << exact;
  }
}

TEST(Determinism, CornellBoxIsBitwiseIdenticalWithGridAndNaive) {
  expect_same_image_with_grid_and_naive(test::assets_dir() / "cornell-box" / "scene.json", 64, 8);
}

TEST(Determinism, LowResolutionBunnyIsBitwiseIdenticalWithGridAndNaive) {
  // Naive tests all 3,676 triangles per ray: a small film keeps this quick.
  expect_same_image_with_grid_and_naive(test::assets_dir() / "bunny-lowres" / "scene_lowres.json", 40, 2);
}

}  // namespace
}  // namespace kappa
