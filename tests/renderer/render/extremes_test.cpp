// The renderer at its extremes: the smallest and a too-large film, blinding
// and lossless materials, a scene with no light, scenes at scales from 1e-6
// to 1e6 and far from the origin, and a million triangles. Each must give a
// finite, right image or a refusal, never a crash, a hang or a speckle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>

#include "accel/factory.h"
#include "renderer/io/exr_input.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

/// A frame on the grid, and what the render says of it: a non-finite sample is
/// dropped from its pixel (so the film stays finite) but counted here.
struct Rendered {
  Film film;
  RenderResult result;
};

Rendered render_on_grid(const Scene& scene, const RenderSettings& settings) {
  const auto accel = make_accelerator("grid", scene.triangles);
  Rendered r{Film(scene.width, scene.height, settings.aov), {}};
  r.result = render(scene, *accel, settings, r.film);
  return r;
}

bool all_finite(const Film& film) {
  for (float v : film.rgb)
    if (!std::isfinite(v)) return false;
  return true;
}

double mean_of(const Film& film) {
  double sum = 0;
  for (float v : film.rgb) sum += v;
  return sum / double(film.rgb.size());
}

/// A closed room (normals in) of albedo `rho` with a square light of side
/// `light_side` and radiance `Ke` just under its ceiling, facing down; the
/// light reflects with albedo `light_rho`.
Scene lit_room(float rho, float light_side, float Ke, float light_rho) {
  Scene s;
  s.materials.push_back(Material{"walls", {rho, rho, rho}, {0, 0, 0}});
  s.materials.push_back(Material{"light", {light_rho, light_rho, light_rho}, {Ke, Ke, Ke}});
  test::add_box(s, {-1, -1, -1}, {1, 1, 1}, /*inward=*/true, 0);
  const float h = light_side / 2, y = 0.99f;
  s.triangles.push_back({{-h, y, -h}, {h, y, -h}, {h, y, h}});  // normal -y: towards the floor
  s.triangles.push_back({{-h, y, -h}, {h, y, h}, {-h, y, h}});
  s.material_of.push_back(1);
  s.material_of.push_back(1);
  s.camera = CameraSpec{{0, 0, -0.9f}, {0, -0.2f, 0}, {0, 1, 0}, 70.0f};
  s.width = s.height = 16;
  return s;
}

TEST(Extremes, AOneByOneFilmRendersOnePixel) {
  test::TempDir dir;
  const auto exr = dir / "one.exr";
  const auto report = dir / "one.json";
  const auto r = test::run_kappa({"render", (test::assets_dir() / "cornell-box" / "scene.json").string(), "--width",
                                  "1", "--height", "1", "--spp", "4", "--out", exr.string(), "--report",
                                  report.string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const ReferenceImage image = read_reference(exr);  // refuses a non-finite or negative value
  EXPECT_EQ(image.width, 1);
  EXPECT_EQ(image.height, 1);
  EXPECT_GT(image.rgb[0] + image.rgb[1] + image.rgb[2], 0.0f);  // the camera looks into the lit box
  const auto j = nlohmann::json::parse(test::read_file(report));
  EXPECT_EQ(j["render"]["width"], 1);
  EXPECT_EQ(j["render"]["height"], 1);
  EXPECT_EQ(j["rays"]["camera"]["count"].get<double>(), 4.0) << j["rays"].dump();  // one per sample
}

TEST(Extremes, AFilmWhoseBuffersExceedMemoryIsRefusedBeforeAllocating) {
  test::TempDir dir;
  const auto exr = dir / "huge.exr";
  // 32768 x 32768 is the largest side accepted; its buffers need about
  // 2^30 pixels x 100 bytes, far beyond this machine's RAM. With the memory
  // limited to 4 GiB, an allocation would fail with bad_alloc (exit 1).
  const auto r = test::run_kappa({"render", (test::assets_dir() / "cornell-box" / "scene.json").string(), "--width",
                                  "32768", "--height", "32768", "--spp", "1", "--out", exr.string()},
                                 {}, 120);
  EXPECT_EQ(r.exit_code, 2) << r.std_err;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r.std_err;
  EXPECT_NE(lines[0].find("film 32768x32768"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("memory"), std::string::npos) << lines[0];
  EXPECT_FALSE(std::filesystem::exists(exr));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(Extremes, ATinyLightOfKeOneMillionGivesAFiniteImage) {
  // A light 1e-3 across (area 1e-6) at Ke = 1e6: its power is that of a unit
  // light of Ke = 1, reached through pdfs of 1e6 and distances of 1e-3.
  const Scene s = lit_room(0.5f, 1e-3f, 1e6f, 0.0f);
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    RenderSettings settings;
    settings.spp = 8;
    settings.light_sampling = strategy;
    const Rendered r = render_on_grid(s, settings);
    EXPECT_EQ(r.result.nonfinite_samples, 0u) << light_sampling_name(strategy);
    EXPECT_TRUE(all_finite(r.film)) << light_sampling_name(strategy);
    if (strategy != LightSampling::bsdf) {  // BSDF sampling alone rarely finds so small a light
      EXPECT_GT(mean_of(r.film), 0.0) << light_sampling_name(strategy);
    }
  }
}

TEST(Extremes, AlbedoOneUnderTheSkyReadsTheSkyWithRussianRoulette) {
  // A convex object never sees itself: with albedo exactly 1 it reads E,
  // however early roulette starts (it never ends a path of throughput 1).
  Scene s;
  s.materials.push_back(Material{"white", {1, 1, 1}, {0, 0, 0}});
  test::add_sphere(s, {0, 0, 0}, 1.0f, 16, 32, false, 0);
  s.environment = {1.0f, 0.5f, 0.25f};
  s.camera = CameraSpec{{0, 0, -3}, {0, 0, 0}, {0, 1, 0}, 30.0f};
  s.width = s.height = 24;
  for (int rr_depth : {0, 1, 5}) {
    RenderSettings settings;
    settings.spp = 4;
    settings.rr_depth = rr_depth;
    settings.aov.albedo = true;
    const Film film = test::render_scene(s, settings, "grid");
    std::size_t on_object = 0;
    for (std::size_t i = 0; i < film.pixels(); ++i) {
      if (film.albedo[3 * i] != 1.0f) continue;  // a sample of this pixel missed the sphere
      ++on_object;
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(film.rgb[3 * i + std::size_t(c)], s.environment[c], 1e-4f * s.environment[c])
            << "pixel " << i << " rr_depth " << rr_depth;
    }
    EXPECT_GT(on_object, film.pixels() / 4);
  }
}

TEST(Extremes, AClosedWhiteRoomEndsAtMaxDepthWithAFiniteImage) {
  // Nothing absorbs: roulette never ends a path, --max-depth does. The
  // radiance gathered grows with the depth allowed (each bounce adds the
  // light's share again).
  const Scene s = lit_room(1.0f, 0.5f, 1.0f, 1.0f);
  RenderSettings settings;
  settings.spp = 2;
  settings.max_depth = 10;
  const Rendered shallow_render = render_on_grid(s, settings);
  settings.max_depth = 1000;
  const Rendered deep_render = render_on_grid(s, settings);
  const Film& shallow = shallow_render.film;
  const Film& deep = deep_render.film;
  EXPECT_EQ(deep_render.result.nonfinite_samples, 0u);
  ASSERT_TRUE(all_finite(shallow));
  ASSERT_TRUE(all_finite(deep));
  std::printf("white room: mean %.4f at max-depth 10, %.4f at 1000\n", mean_of(shallow), mean_of(deep));
  EXPECT_GT(mean_of(deep), 20 * mean_of(shallow));
}

TEST(Extremes, NoEmittersAndABlackSkyAreExactlyBlack) {
  Scene s;
  s.materials.push_back(Material{"grey", {0.7f, 0.7f, 0.7f}, {0, 0, 0}});
  test::add_box(s, {-2, -1, -2}, {2, 0, 2}, false, 0);
  test::add_sphere(s, {0, 0.5f, 0}, 0.5f, 8, 16, false, 0);
  s.camera = CameraSpec{{0, 1, -4}, {0, 0, 0}, {0, 1, 0}, 40.0f};
  s.width = s.height = 16;
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    RenderSettings settings;
    settings.spp = 4;
    settings.light_sampling = strategy;
    settings.aov.variance = true;
    const Film film = test::render_scene(s, settings, "grid");
    for (float v : film.rgb) ASSERT_EQ(v, 0.0f) << light_sampling_name(strategy);
    for (float v : film.variance) ASSERT_EQ(v, 0.0f) << light_sampling_name(strategy);
  }
}

/// The Cornell box with every vertex and the camera mapped by p * scale + shift.
Scene transformed_cornell(double scale, double shift) {
  Warnings warnings;
  Scene s = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  const auto map = [&](const Vec3f& p) {
    return Vec3f{float(double(p.x) * scale + shift), float(double(p.y) * scale + shift),
                 float(double(p.z) * scale + shift)};
  };
  for (Triangle& t : s.triangles) t = {map(t.v0), map(t.v1), map(t.v2)};
  s.camera.eye = map(s.camera.eye);
  s.camera.look_at = map(s.camera.look_at);
  s.width = s.height = 32;
  return s;
}

// Radiance does not depend on the scene's unit, so the Cornell box at scales
// 1e-6 and 1e6, and shifted by 1e6 (where a float's step is 1/16 against a
// box 556 across), renders the image of scale 1. The same seed draws the same
// samples, so most pixels agree to rounding; a sample whose path rounding
// turns elsewhere moves its pixel by noise. A self-intersection would darken
// pixels everywhere (every shadow ray blocked): speckles are counted as
// pixels more than 30 % away from the reference, and the mean must hold to
// 1 %. Measured: no speckled pixel at 16 spp (3 of 1024 at the sanitizer
// suite's 4), the mean within 0.03 % (0.04 %); with a fixed offset of 1e-4
// instead of one scaled to the point's rounding error, 325 speckled pixels at
// scale 1e-6 and 85 shifted by 1e6.
TEST(Extremes, ScaledAndShiftedScenesRenderTheSameImage) {
  RenderSettings settings;
  settings.spp = test::scaled(16, 4);
  const Film reference = test::render_scene(transformed_cornell(1, 0), settings, "grid");
  const double reference_mean = mean_of(reference);
  ASSERT_GT(reference_mean, 0.0);
  struct Case {
    double scale, shift;
  };
  for (const Case c : {Case{1e-6, 0}, Case{1e6, 0}, Case{1, 1e6}}) {
    const Rendered r = render_on_grid(transformed_cornell(c.scale, c.shift), settings);
    const Film& film = r.film;
    EXPECT_EQ(r.result.nonfinite_samples, 0u);
    ASSERT_TRUE(all_finite(film));
    std::size_t speckles = 0;
    for (std::size_t i = 0; i < film.pixels(); ++i) {
      double a = 0, b = 0;
      for (int k = 0; k < 3; ++k) {
        a += reference.rgb[3 * i + std::size_t(k)];
        b += film.rgb[3 * i + std::size_t(k)];
      }
      if (std::abs(a - b) > 0.3 * std::max(a, b) + 1e-3 * reference_mean) ++speckles;
    }
    const double mean_change = mean_of(film) / reference_mean - 1;
    std::printf("scale %g shift %g: %zu speckled pixels of %zu, mean %+.4f %%\n", c.scale, c.shift, speckles,
                film.pixels(), 100 * mean_change);
    EXPECT_LE(speckles, film.pixels() / 100) << "scale " << c.scale << " shift " << c.shift;
    EXPECT_LT(std::abs(mean_change), 0.01) << "scale " << c.scale << " shift " << c.shift;
  }
}

// A million triangles (a quarter under KAPPA_TEST_SCALE=0.25) written as OBJ,
// loaded, built and rendered with the default settings (statistics on): the
// per-cell counters fit or fall back with a note, never fail to allocate.
// The 10^7 case is measured in the #20 note (tools/make_soup.py).
TEST(Extremes, AMillionTriangleSoupLoadsBuildsAndRendersWithDefaults) {
  test::TempDir dir;
  const auto obj = dir / "soup.obj";
  const int n = test::scaled(1000000);
  {
    std::FILE* f = std::fopen(obj.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1, 1);
    const float edge = 2.0f / std::sqrt(float(n));  // constant total area: the paper's O(N) storage case
    for (int i = 0; i < n; ++i) {
      const float cx = u(rng), cy = u(rng), cz = u(rng);
      for (int v = 0; v < 3; ++v)
        std::fprintf(f, "v %.6f %.6f %.6f\n", cx + edge * u(rng), cy + edge * u(rng), cz + edge * u(rng));
      std::fprintf(f, "f -3 -2 -1\n");
    }
    ASSERT_EQ(std::fclose(f), 0);
  }
  const auto report = dir / "soup.json";
  const auto r = test::run_kappa({"render", obj.string(), "--width", "32", "--height", "32", "--spp", "1", "--out",
                                  (dir / "soup.exr").string(), "--report", report.string()});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const auto j = nlohmann::json::parse(test::read_file(report));
  EXPECT_EQ(j["grid2"]["N"].get<double>(), double(n)) << j["grid2"].dump();  // the default accelerator
  const ReferenceImage image = read_reference(dir / "soup.exr");
  EXPECT_EQ(image.width, 32);
}

}  // namespace
}  // namespace kappa
