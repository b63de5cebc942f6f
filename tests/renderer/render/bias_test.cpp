// Bias is a bug: estimators that must agree in expectation do, within 4
// standard errors of the mean over many pixels, and each test first shows
// that it could see a 1 % bias (4 standard errors below 1 % of the mean).
// The difference is taken pixel by pixel between two independent renders,
// so the image's own variation across pixels cancels and only noise is left.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "renderer/render/path_variant.h"
#include "renderer/render/render_helpers.h"
#include "test_util.h"

namespace kappa {
namespace {

struct Agreement {
  double mean = 0;  ///< of the first image, over pixels and channels
  double diff = 0;  ///< mean of (a - b) over pixels and channels
  double se = 0;    ///< standard error of diff, pixels taken as independent
};

Agreement agreement(const Film& a, const Film& b) {
  double sum_a = 0, sum_d = 0, sum_d2 = 0;
  const std::size_t n = a.pixels();
  for (std::size_t i = 0; i < n; ++i) {
    double d = 0;  // a pixel's channels share their paths: one value per pixel
    for (int c = 0; c < 3; ++c) {
      sum_a += a.rgb[3 * i + std::size_t(c)];
      d += double(a.rgb[3 * i + std::size_t(c)]) - b.rgb[3 * i + std::size_t(c)];
    }
    d /= 3;
    sum_d += d;
    sum_d2 += d * d;
  }
  Agreement g;
  g.mean = sum_a / double(3 * n);
  g.diff = sum_d / double(n);
  g.se = std::sqrt(std::max(0.0, sum_d2 / double(n) - g.diff * g.diff) / double(n - 1));
  return g;
}

/// `spp`: the smaller of the two images' sample counts before scaling, which
/// sets how much KAPPA_TEST_SCALE widens the 1 % this test can resolve.
void expect_agree(const Film& a, const Film& b, const std::string& what, int spp) {
  const Agreement g = agreement(a, b);
  const double resolvable = 0.01 * test::noise_widening(spp);
  std::printf("%s: mean %.5f, difference %+.3f %% (%.2f SE), 4 SE = %.3f %%\n", what.c_str(), g.mean,
              100 * g.diff / g.mean, g.se > 0 ? g.diff / g.se : 0.0, 400 * g.se / g.mean);
  EXPECT_LT(4 * g.se, resolvable * g.mean) << what << ": too noisy to see a " << 100 * resolvable << " % bias";
  EXPECT_LT(std::abs(g.diff), 4 * g.se) << what << ": differ by " << 100 * g.diff / g.mean << " %";
}

/// Renders at settings.spp scaled by KAPPA_TEST_SCALE.
Film render_with(const Scene& scene, RenderSettings settings, std::uint64_t seed) {
  settings.seed = seed;
  settings.spp = test::scaled(settings.spp);
  return test::render_scene(scene, settings, "grid");
}

/// A floor, a wall and a block lit by a small, bright square light well above
/// them (or by the sky alone): BSDF sampling finds such a light rarely, light
/// sampling every time.
Scene small_light_room(bool light, bool sky) {
  Scene s;
  s.materials.push_back(Material{"white", {0.7f, 0.7f, 0.7f}, {0, 0, 0}});
  s.materials.push_back(Material{"light", {0, 0, 0}, {50, 45, 38}});
  s.materials.push_back(Material{"red", {0.6f, 0.2f, 0.2f}, {0, 0, 0}});
  test::add_box(s, {-2, -1, -2}, {2, 0, 2}, false, 0);
  test::add_box(s, {-2, 0, 1.5f}, {2, 2, 2}, false, 0);
  test::add_box(s, {-0.5f, 0, -0.5f}, {0.5f, 0.8f, 0.5f}, false, 2);
  if (light) test::add_box(s, {-0.3f, 2.5f, -0.3f}, {0.3f, 2.55f, 0.3f}, false, 1);
  if (sky) s.environment = {0.4f, 0.5f, 0.6f};
  s.camera = CameraSpec{{0, 1.5f, -4}, {0, 0.4f, 0}, {0, 1, 0}, 40.0f};
  s.width = s.height = 96;
  return s;
}

// Russian roulette ends paths early but divides what survives by the
// survival probability: the same mean as paths that run to --max-depth.
TEST(Bias, RussianRouletteOnAndOffAgree) {
  const Scene scene = small_light_room(true, true);
  RenderSettings settings;
  settings.spp = 128;
  settings.rr_depth = 1;  // from the first bounce: the most paths it can end
  const Film with_rr = render_with(scene, settings, 1);
  settings.rr_depth = -1;
  const Film without = render_with(scene, settings, 2);
  expect_agree(with_rr, without, "room, roulette from bounce 1 against none", 128);
}

// MIS, light sampling alone and BSDF sampling alone are three estimators of
// the same integral: under a small bright light, and under the sky.
TEST(Bias, MisNeeAndBsdfAgreeUnderASmallBrightLight) {
  const Scene scene = small_light_room(true, false);
  RenderSettings settings;
  settings.spp = 64;
  settings.max_depth = 2;  // truncated alike under every strategy: the same mean, cheaper BSDF paths
  const Film mis = render_with(scene, settings, 1);
  settings.light_sampling = LightSampling::nee;
  const Film nee = render_with(scene, settings, 2);
  settings.light_sampling = LightSampling::bsdf;
  settings.spp = 1024;  // it finds the light about once in 40 samples
  const Film bsdf = render_with(scene, settings, 3);
  expect_agree(mis, nee, "small light, mis against nee", 64);
  expect_agree(mis, bsdf, "small light, mis against bsdf", 64);
}

TEST(Bias, MisNeeAndBsdfAgreeUnderTheSky) {
  const Scene scene = small_light_room(false, true);
  RenderSettings settings;
  settings.spp = 64;
  const Film mis = render_with(scene, settings, 1);
  settings.light_sampling = LightSampling::nee;
  const Film nee = render_with(scene, settings, 2);
  settings.light_sampling = LightSampling::bsdf;
  const Film bsdf = render_with(scene, settings, 3);
  expect_agree(mis, nee, "sky, mis against nee", 64);
  expect_agree(mis, bsdf, "sky, mis against bsdf", 64);
}

// Stratifying a dimension must not move the mean of the decision that reads it.
TEST(Bias, EverySamplerAgreesWithIndependentSampling) {
  const Scene scene = small_light_room(true, true);  // both kinds of light: the light choice matters
  RenderSettings settings;
  settings.spp = 128;
  settings.sampler = SamplerKind::independent;
  const Film independent = render_with(scene, settings, 1);
  for (SamplerKind k : {SamplerKind::stratified, SamplerKind::sobol}) {
    settings.sampler = k;
    expect_agree(independent, render_with(scene, settings, 2), std::string("room, independent against ") + sampler_name(k),
                 128);
  }
}

/// The room with the materials' lobes: a glossy floor, a rough metal block,
/// a rough and a smooth glass block, under the small light and the sky.
Scene material_room() {
  Scene s = small_light_room(true, true);
  Material glossy{"glossy", {0.7f, 0.7f, 0.7f}, {0, 0, 0}};
  glossy.specular = 0.5f;
  glossy.roughness = 0.3f;
  Material metal{"metal", {0.9f, 0.6f, 0.5f}, {0, 0, 0}};
  metal.metallic = 1;
  metal.roughness = 0.4f;
  Material rough_glass{"rough glass", {1, 1, 1}, {0, 0, 0}};
  rough_glass.transmission = 1;
  rough_glass.roughness = 0.3f;
  rough_glass.ior = 1.5f;
  Material smooth_glass = rough_glass;
  smooth_glass.roughness = 0;
  const auto first = std::uint32_t(s.materials.size());
  s.materials.insert(s.materials.end(), {glossy, metal, rough_glass, smooth_glass});
  for (std::uint32_t& m : s.material_of)
    if (m == 0) m = first;  // the floor and the wall: glossy
    else if (m == 2) m = first + 1;  // the block: metal
  test::add_box(s, {-1.6f, 0, -1.0f}, {-0.9f, 0.6f, -0.3f}, false, first + 2);
  test::add_box(s, {0.9f, 0, -1.0f}, {1.6f, 0.6f, -0.3f}, false, first + 3);
  return s;
}

// The three strategies agree through glossy, metal and glass lobes too (MIS
// weights of a mixture of lobes, delta lobes taking no light sample).
TEST(Bias, MisNeeAndBsdfAgreeThroughMaterials) {
  const Scene scene = material_room();
  RenderSettings settings;
  settings.spp = 64;
  settings.max_depth = 3;
  const Film mis = render_with(scene, settings, 1);
  settings.light_sampling = LightSampling::nee;
  settings.spp = 256;  // light sampling alone is noisy on the glossy floor's reflection of the light
  const Film nee = render_with(scene, settings, 2);
  settings.light_sampling = LightSampling::bsdf;
  settings.spp = 1024;
  const Film bsdf = render_with(scene, settings, 3);
  expect_agree(mis, nee, "materials, mis against nee", 64);
  expect_agree(mis, bsdf, "materials, mis against bsdf", 64);
}

// Russian roulette through refraction (its throughput with the 1/eta^2 undone)
// and stratified lobe choices keep the mean.
TEST(Bias, RouletteAndSamplersAgreeThroughMaterials) {
  const Scene scene = material_room();
  RenderSettings settings;
  settings.spp = 128;
  settings.max_depth = 12;  // both truncated alike
  settings.sampler = SamplerKind::independent;
  settings.rr_depth = 1;
  const Film with_rr = render_with(scene, settings, 1);
  settings.rr_depth = -1;
  const Film without = render_with(scene, settings, 2);
  expect_agree(with_rr, without, "materials, roulette from bounce 1 against none", 128);
  settings.rr_depth = 1;
  settings.sampler = SamplerKind::sobol;
  expect_agree(with_rr, render_with(scene, settings, 3), "materials, independent against sobol", 128);
}

}  // namespace
}  // namespace kappa
