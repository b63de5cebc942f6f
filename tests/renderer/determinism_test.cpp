// Pixels depend on (seed, pixel, sample index) only: never on thread count.
#include <gtest/gtest.h>

#include <cstring>

#include "render_helpers.h"
#include "renderer/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

bool bitwise_equal(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(Determinism, CornellBoxIsBitwiseIdenticalAt1And2And4Threads) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  scene.width = scene.height = 48;
  RenderSettings settings;
  settings.spp = 8;
  settings.seed = 7;
  settings.aov = AovSelection{true, true, true};
  settings.threads = 1;
  const Film one = test::render_scene(scene, settings);
  for (int threads : {2, 4}) {
    settings.threads = threads;
    const Film many = test::render_scene(scene, settings);
    EXPECT_TRUE(bitwise_equal(one.rgb, many.rgb)) << threads << " threads";
    EXPECT_TRUE(bitwise_equal(one.albedo, many.albedo)) << threads << " threads";
    EXPECT_TRUE(bitwise_equal(one.normal, many.normal)) << threads << " threads";
    EXPECT_TRUE(bitwise_equal(one.depth, many.depth)) << threads << " threads";
  }
  // The seed does matter: a different one gives a different image.
  settings.seed = 8;
  EXPECT_FALSE(bitwise_equal(one.rgb, test::render_scene(scene, settings).rgb));
}

TEST(Determinism, ImageIsFiniteAndLitWhereTheLightIs) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  EXPECT_TRUE(warnings.empty());
  scene.width = scene.height = 32;
  RenderSettings settings;
  settings.spp = 4;
  const Film film = test::render_scene(scene, settings);
  double sum = 0;
  for (float v : film.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    sum += v;
  }
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace kappa
