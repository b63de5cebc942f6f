// Scenes whose rendered value is known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "renderer/render/lights.h"
#include "renderer/render/render_helpers.h"
#include "test_util.h"

namespace kappa {
namespace {

/// A closed box (normals facing in) in which every surface has albedo rho
/// and emits Le, seen from its centre: L = Le / (1 - rho) everywhere.
Scene furnace(float rho, float Le) {
  Scene s;
  s.materials.push_back(Material{"furnace", {rho, rho, rho}, {Le, Le, Le}});
  test::add_box(s, {-1, -1, -1}, {1, 1, 1}, /*inward=*/true, 0);
  s.camera = CameraSpec{{0.1f, -0.05f, 0.02f}, {0.3f, 0.2f, 1.0f}, {0, 1, 0}, 90.0f};
  s.width = s.height = 64;
  return s;
}

void expect_furnace(float rho, int spp, int max_depth, SamplerKind sampler = SamplerKind::independent,
                    LightSampling strategy = LightSampling::mis, int rr_depth = 3) {
  const float Le = 0.5f;
  const double expected = Le / (1.0 - rho);
  RenderSettings settings;
  settings.sampler = sampler;
  settings.light_sampling = strategy;
  settings.rr_depth = rr_depth;
  settings.spp = test::scaled(spp);
  settings.max_depth = max_depth;
  const double widening = test::noise_widening(spp);
  const Film film = test::render_scene(furnace(rho, Le), settings);
  for (int c = 0; c < 3; ++c) {
    const auto stats = test::channel_stats(film, c);
    SCOPED_TRACE("rho " + std::to_string(rho) + " channel " + std::to_string(c) + " mean " +
                 std::to_string(stats.mean) + " se " + std::to_string(stats.standard_error));
    std::printf("furnace rho=%.2f max_depth=%d channel %d: mean %.5f expected %.5f rel.err %.3f%% (%.2f SE)\n", rho,
                max_depth, c, stats.mean, expected, 100 * std::abs(stats.mean - expected) / expected,
                std::abs(stats.mean - expected) / stats.standard_error);
    EXPECT_LT(std::abs(stats.mean - expected), 0.01 * widening * expected);
    EXPECT_LT(std::abs(stats.mean - expected), 4.0 * stats.standard_error + 1e-6 * expected);
  }
}

TEST(Analytic, FurnaceConvergesToLeOverOneMinusRho) { expect_furnace(0.5f, 64, 32); }

TEST(Analytic, FurnaceWithRho099ExercisesRussianRoulette) { expect_furnace(0.99f, 16, 2000); }

// Every sampler converges to the same value: stratifying a dimension must
// not bias the decision that reads it.
TEST(Analytic, FurnaceUnderEverySampler) {
  for (SamplerKind k : {SamplerKind::stratified, SamplerKind::sobol}) {
    SCOPED_TRACE(sampler_name(k));
    expect_furnace(0.5f, 64, 32, k);
    expect_furnace(0.99f, 16, 2000, k);
  }
}

// Deep paths stay exact: at --max-depth 1000, with and without Russian
// roulette, under MIS and BSDF sampling (rho^1001 is 1e-46: the truncation
// is far below the noise). Light sampling alone is too noisy in a room whose
// every wall is a light to see 1 % here; Bias.* compares it with the others.
TEST(Analytic, FurnaceStaysExactAtLargeMaxDepth) {
  for (LightSampling s : {LightSampling::mis, LightSampling::bsdf}) {
    SCOPED_TRACE(light_sampling_name(s));
    expect_furnace(0.9f, 2, 1000, SamplerKind::independent, s, -1);  // every path 1000 bounces long
    expect_furnace(0.9f, 64, 1000, SamplerKind::independent, s, 3);
  }
}

// Truncated at d bounces (no Russian roulette), the furnace holds the first
// d + 1 terms of its series: Le (1 - rho^(d+1)) / (1 - rho). Next-event
// estimation at the last vertex and BSDF sampling of the light after it are
// weighted by MIS, so each bounce's light is counted once, whichever found it.
TEST(Analytic, FurnaceTruncatedAtMaxDepthHoldsTheFirstTermsOfItsSeries) {
  const float rho = 0.5f, Le = 0.5f;
  for (int d : {0, 1, 2, 3}) {
    RenderSettings settings;
    settings.spp = 16;
    settings.max_depth = d;
    settings.rr_depth = -1;
    const Film film = test::render_scene(furnace(rho, Le), settings);
    const double expected = Le * (1.0 - std::pow(double(rho), d + 1)) / (1.0 - rho);
    for (int c = 0; c < 3; ++c) {
      const auto stats = test::channel_stats(film, c);
      EXPECT_LT(std::abs(stats.mean - expected), 0.01 * expected) << "max_depth " << d << " mean " << stats.mean;
      EXPECT_LT(std::abs(stats.mean - expected), 4.0 * stats.standard_error + 1e-6 * expected) << "max_depth " << d;
    }
  }
}

TEST(Analytic, EmitterSeenDirectlyReadsExactlyKe) {
  Scene s;
  s.materials.push_back(Material{"light", {0, 0, 0}, {3.0f, 2.0f, 0.25f}});
  // A large quad at z = 5 facing the camera (normal -z), filling the view.
  s.triangles.push_back({{-100, -100, 5}, {-100, 100, 5}, {100, 100, 5}});
  s.triangles.push_back({{-100, -100, 5}, {100, 100, 5}, {100, -100, 5}});
  s.material_of = {0, 0};
  s.camera = CameraSpec{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 40.0f};
  s.width = s.height = 16;
  RenderSettings settings;
  settings.spp = 8;
  const Film film = test::render_scene(s, settings);
  for (std::size_t i = 0; i < film.pixels(); ++i) {
    ASSERT_EQ(film.rgb[3 * i + 0], 3.0f);
    ASSERT_EQ(film.rgb[3 * i + 1], 2.0f);
    ASSERT_EQ(film.rgb[3 * i + 2], 0.25f);
  }
  // One-sided: from behind, the emitter is black.
  s.camera = CameraSpec{{0, 0, 10}, {0, 0, 5}, {0, 1, 0}, 40.0f};
  const Film back = test::render_scene(s, settings);
  for (float v : back.rgb) ASSERT_EQ(v, 0.0f);
}

TEST(Analytic, NothingInViewReadsExactlyTheEnvironment) {
  Scene s;
  s.materials.push_back(Material{"grey", {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  s.triangles.push_back({{-1, -1, -5}, {1, -1, -5}, {0, 1, -5}});  // behind the camera
  s.material_of = {0};
  s.environment = {0.2f, 0.5f, 0.7f};
  s.camera = CameraSpec{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 60.0f};
  s.width = s.height = 16;
  RenderSettings settings;
  settings.spp = 4;
  const Film film = test::render_scene(s, settings);
  for (std::size_t i = 0; i < film.pixels(); ++i) {
    ASSERT_EQ(film.rgb[3 * i + 0], 0.2f);
    ASSERT_EQ(film.rgb[3 * i + 1], 0.5f);
    ASSERT_EQ(film.rgb[3 * i + 2], 0.7f);
  }
}

/// A convex diffuse object under a constant sky never sees itself, so it
/// reads rho * E at any depth. With the sky sampled like the BSDF, MIS gives
/// every sample exactly rho * E up to rounding: a tight check of the weights.
TEST(Analytic, ConvexObjectUnderSkyReadsRhoTimesE) {
  Scene s;
  const float rho = 0.6f;
  s.materials.push_back(Material{"object", {rho, rho, rho}, {0, 0, 0}});
  test::add_sphere(s, {0, 0, 0}, 1.0f, 16, 32, false, 0);
  s.environment = {1.0f, 0.5f, 0.25f};
  s.camera = CameraSpec{{0, 0, -3}, {0, 0, 0}, {0, 1, 0}, 30.0f};
  s.width = s.height = 32;
  for (int depth : {1, 2, 5, 32}) {
    RenderSettings settings;
    settings.spp = 8;
    settings.max_depth = depth;
    settings.aov.albedo = true;
    const Film film = test::render_scene(s, settings);
    std::size_t on_object = 0;
    for (std::size_t i = 0; i < film.pixels(); ++i) {
      if (film.albedo[3 * i] != rho) continue;  // a sample of this pixel missed the sphere
      ++on_object;
      for (int c = 0; c < 3; ++c) {
        const float expected = rho * (c == 0 ? 1.0f : c == 1 ? 0.5f : 0.25f);
        ASSERT_NEAR(film.rgb[3 * i + std::size_t(c)], expected, 1e-4f * expected)
            << "pixel " << i << " depth " << depth;
      }
    }
    EXPECT_GT(on_object, film.pixels() / 4);
  }
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(Analytic, EmitterTooDimToBeALightStillShinesThroughBsdfSampling) {
  // A ceiling emitter 1e60 times dimmer than another light: its share of the
  // light pmf rounds to 0 in float, so next-event estimation never picks it
  // (pmf_of_triangle == 0, the branch under test). The bright light faces
  // away and lights nothing here. A diffuse floor under the dim ceiling must
  // still see it, by BSDF sampling with the whole MIS weight: L = rho Le F,
  // with F ~ 0.99 the part of the floor's cosine-weighted hemisphere the
  // 20 x 20 ceiling at height 1 covers.
  Scene s;
  s.materials.push_back(Material{"floor", {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  s.materials.push_back(Material{"dim", {0, 0, 0}, {1e-30f, 1e-30f, 1e-30f}});
  s.materials.push_back(Material{"bright", {0, 0, 0}, {1e30f, 1e30f, 1e30f}});
  s.triangles.push_back({{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}});
  s.triangles.push_back({{-10, 0, -10}, {10, 0, 10}, {10, 0, -10}});
  s.triangles.push_back({{-10, 1, -10}, {10, 1, 10}, {-10, 1, 10}});  // faces down
  s.triangles.push_back({{-10, 1, -10}, {10, 1, -10}, {10, 1, 10}});
  s.triangles.push_back({{0, 5, 0}, {0, 5, 1}, {1, 5, 0}});  // above the ceiling, facing up
  s.material_of = {0, 0, 1, 1, 2};
  s.camera = CameraSpec{{0, 0.5f, 0}, {0, 0, 0.01f}, {0, 0, 1}, 60.0f};
  s.width = s.height = 8;
  const Lights lights(s);
  ASSERT_EQ(lights.pmf_of_triangle(2), 0.0f);  // too dim to be a light
  ASSERT_GT(lights.pmf_of_triangle(4), 0.0f);
  // Under nee too, whose BSDF-sampled rays count only the emitters light
  // sampling cannot pick (this one), and under bsdf.
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    SCOPED_TRACE(light_sampling_name(strategy));
    RenderSettings settings;
    settings.spp = 16;
    settings.light_sampling = strategy;
    const Film film = test::render_scene(s, settings);
    double sum = 0;
    for (float v : film.rgb) {
      ASSERT_TRUE(std::isfinite(v));
      sum += v;
    }
    const double mean = sum / double(film.rgb.size());
    EXPECT_GT(mean, 0.5e-30 * 0.9);  // it shines
    EXPECT_LT(mean, 0.5e-30 * 1.0);
  }
}

/// The part of a floor point's cosine-weighted hemisphere that a square of
/// half-side w, centred at height h above it and parallel to the floor,
/// covers (the view factor: four corner rectangles, each
/// (1/2pi)[A/sqrt(1+A^2) atan(A/sqrt(1+A^2))] twice, with A = w/h).
double square_view_factor(double w, double h) {
  const double A = w / h, s = A / std::sqrt(1 + A * A);
  return 4.0 / std::numbers::pi * s * std::atan(s);
}

/// A black square emitter of half-side w at height h, facing down.
void add_ceiling_light(Scene& s, float w, float h, std::uint32_t material) {
  s.triangles.push_back({{-w, h, -w}, {w, h, w}, {-w, h, w}});
  s.triangles.push_back({{-w, h, -w}, {w, h, -w}, {w, h, w}});
  s.material_of.insert(s.material_of.end(), {material, material});
}

/// A diffuse floor (albedo 0.5) seen from above in a 0.5 degree field of
/// view, so every pixel shows (almost) the point under the lights. Small, so
/// that the environment's share of the light pmf (by power, which grows with
/// the scene's radius) stays far from 1 and its pdf matters.
Scene floor_under_lights() {
  Scene s;
  s.materials.push_back(Material{"floor", {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  s.triangles.push_back({{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}});
  s.triangles.push_back({{-3, 0, -3}, {3, 0, 3}, {3, 0, -3}});
  s.material_of = {0, 0};
  s.camera = CameraSpec{{0, 0.5f, 0}, {0, 0, 1e-4f}, {0, 0, 1}, 0.5f};
  s.width = s.height = 4;
  return s;
}

void expect_floor_radiance(const Scene& s, double expected) {
  RenderSettings settings;
  settings.spp = 4096;
  const Film film = test::render_scene(s, settings);
  for (int c = 0; c < 3; ++c) {
    const auto stats = test::channel_stats(film, c);
    EXPECT_LT(std::abs(stats.mean - expected), 0.02 * expected) << "channel " << c << " mean " << stats.mean;
    EXPECT_LT(std::abs(stats.mean - expected), 4.0 * stats.standard_error + 1e-6 * expected) << "channel " << c;
  }
}

// Two lights of unequal power (so unequal light pdfs), the nearer one hiding
// the middle of the farther from the floor point: direct light from both,
// found by next-event estimation and BSDF sampling under MIS, is
// rho (Le1 F1 + Le2 (F2 - F1)).
TEST(Analytic, TwoLightsUnderMisMatchTheirViewFactors) {
  Scene s = floor_under_lights();
  s.materials.push_back(Material{"near", {0, 0, 0}, {4, 4, 4}});
  s.materials.push_back(Material{"far", {0, 0, 0}, {1, 1, 1}});
  add_ceiling_light(s, 1, 1, 1);  // tan 45 degrees: inside the far light's pyramid (tan 53)
  add_ceiling_light(s, 4, 3, 2);
  const double F1 = square_view_factor(1, 1), F2 = square_view_factor(4, 3);
  expect_floor_radiance(s, 0.5 * (4 * F1 + 1 * (F2 - F1)));
}

// A light and the environment: rho (Le F + L_env (1 - F)).
TEST(Analytic, ALightAndTheEnvironmentUnderMisMatchTheirViewFactors) {
  Scene s = floor_under_lights();
  s.materials.push_back(Material{"light", {0, 0, 0}, {8, 8, 8}});
  add_ceiling_light(s, 1, 2, 1);
  s.environment = {0.25f, 0.25f, 0.25f};
  const Lights lights(s);
  ASSERT_GT(lights.pmf_environment(), 0.2f);  // both strategies matter
  ASSERT_LT(lights.pmf_environment(), 0.8f);
  const double F = square_view_factor(1, 2);
  expect_floor_radiance(s, 0.5 * (8 * F + 0.25 * (1 - F)));
}

// The environment beside a light that lights nothing (it faces up, above a
// black square): the light takes about half the light pmf, so the
// environment's NEE and BSDF strategies both carry weight, and the floor
// reads rho L_env (1 - F), F the square's view factor. A wrong environment
// pdf in either strategy's MIS weight shows here.
TEST(Analytic, TheEnvironmentBesideALightThatLightsNothingUnderMis) {
  Scene s;
  s.materials.push_back(Material{"floor", {0.5f, 0.5f, 0.5f}, {0, 0, 0}});
  s.materials.push_back(Material{"black", {0, 0, 0}, {0, 0, 0}});
  s.materials.push_back(Material{"light", {0, 0, 0}, {90, 90, 90}});
  s.triangles.push_back({{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}});
  s.triangles.push_back({{-1, 0, -1}, {1, 0, 1}, {1, 0, -1}});
  s.material_of = {0, 0};
  add_ceiling_light(s, 1, 2, 1);  // the black square: emits nothing
  s.triangles.push_back({{0, 2.5f, 0}, {0, 2.5f, 1}, {1, 2.5f, 0}});  // facing up, inside the square's shadow
  s.material_of.push_back(2);
  s.environment = {1, 1, 1};
  s.camera = CameraSpec{{0, 0.5f, 0}, {0, 0, 1e-4f}, {0, 0, 1}, 0.5f};
  s.width = s.height = 4;
  const Lights lights(s);
  ASSERT_GT(lights.pmf_environment(), 0.35f);
  ASSERT_LT(lights.pmf_environment(), 0.65f);
  expect_floor_radiance(s, 0.5 * 1.0 * (1 - square_view_factor(1, 2)));
}

}  // namespace
}  // namespace kappa
