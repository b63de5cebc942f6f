// Environment images (renderer/render/environment_map.h): sampling by the
// image's luminance x sin(theta) against its density (chi-square over the
// texels), the density agreeing with itself and integrating to 1, the
// rotation, a diffuse plane under a two-valued image rendering the
// irradiance computed by hand with every light-sampling strategy, and a
// constant image loaded as today's constant environment.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "renderer/bsdf/chi2.h"
#include "renderer/render/environment_map.h"
#include "renderer/render/render_helpers.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/image/image_library.h"
#include "test_util.h"

namespace kappa {
namespace {

constexpr double kPi = std::numbers::pi;

EnvironmentImage random_image(int w, int h, std::uint32_t seed) {
  EnvironmentImage img;
  img.width = w;
  img.height = h;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (int i = 0; i < w * h; ++i)
    for (int c = 0; c < 3; ++c) img.rgb.push_back(uni(rng));
  // A hot spot, 500 times the rest, as a sun.
  for (int c = 0; c < 3; ++c) img.rgb[3 * std::size_t(h / 3 * w + w / 4) + std::size_t(c)] = 500.0f;
  // A black row: no sample may land there.
  for (int x = 0; x < w; ++x)
    for (int c = 0; c < 3; ++c) img.rgb[3 * std::size_t((h - 2) * w + x) + std::size_t(c)] = 0.0f;
  return img;
}

/// The texel a direction falls in, unrotated (the map's documented orientation).
std::size_t texel_of(const Vec3f& d, int w, int h) {
  const double u = 0.5 + std::atan2(double(d.z), double(d.x)) / (2 * kPi);
  const double v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / kPi;
  const int x = std::clamp(int(u * w), 0, w - 1), y = std::clamp(int(v * h), 0, h - 1);
  return std::size_t(y * w + x);
}

TEST(EnvironmentMap, SamplesFollowLuminanceTimesSinThetaByChiSquare) {
  const int w = 32, h = 16;
  const EnvironmentImage img = random_image(w, h, 5);
  const EnvironmentMap env(img, 0.0f);
  std::vector<double> expected(std::size_t(w * h));
  double total = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* t = &img.rgb[3 * std::size_t(y * w + x)];
      const double f = (0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]) * std::sin(kPi * (y + 0.5) / h);
      expected[std::size_t(y * w + x)] = f;
      total += f;
    }
  const int n = 400000;
  std::vector<double> observed(expected.size(), 0.0);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  int mismatched_pdf = 0;
  for (int k = 0; k < n; ++k) {
    const auto s = env.sample(uni(rng), uni(rng));
    ASSERT_TRUE(s.has_value());
    observed[texel_of(s->wi, w, h)] += 1;
    // The density of the drawn direction, asked again, is the one the sample gave.
    mismatched_pdf += std::abs(env.pdf(s->wi) / s->pdf - 1.0f) > 1e-3f;
    if (k < 1000) {
      EXPECT_EQ(s->Le, env.Le(s->wi)) << k;
    }
  }
  EXPECT_LE(mismatched_pdf, n / 1000);  // only at texel edges, by rounding
  // Pearson's chi-square, bins of expected count < 5 pooled.
  double chi2 = 0, pooled_e = 0, pooled_o = 0;
  int dof = -1;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const double e = expected[i] / total * n;
    if (e == 0) {
      EXPECT_EQ(observed[i], 0.0) << "texel " << i << " has no weight";
      continue;
    }
    if (e < 5) {
      pooled_e += e;
      pooled_o += observed[i];
      continue;
    }
    chi2 += (observed[i] - e) * (observed[i] - e) / e;
    ++dof;
  }
  if (pooled_e > 0) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++dof;
  }
  const double p = test::chi2::chi2_pvalue(chi2, dof);
  EXPECT_GT(p, 0.01) << "chi2 " << chi2 << " dof " << dof;
}

TEST(EnvironmentMap, TheDensityIntegratesToOneOverTheSphere) {
  const EnvironmentImage img = random_image(16, 8, 9);
  for (float rotation : {0.0f, 37.0f}) {
    const EnvironmentMap env(img, rotation);
    const int nt = 800, np = 1600;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
      const double theta = kPi * (i + 0.5) / nt;
      for (int j = 0; j < np; ++j) {
        const double phi = 2 * kPi * (j + 0.5) / np;
        const Vec3f d{float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi))};
        sum += double(env.pdf(d)) * std::sin(theta);
      }
    }
    sum *= (kPi / nt) * (2 * kPi / np);
    EXPECT_NEAR(sum, 1.0, 2e-3) << rotation;
  }
}

TEST(EnvironmentMap, RotationTurnsTheImageAboutUp) {
  const EnvironmentImage img = random_image(16, 8, 2);
  const EnvironmentMap plain(img, 0.0f), turned(img, 90.0f);
  // +90 degrees takes +x (the image's centre) to -z.
  EXPECT_EQ(turned.Le(Vec3f{0, 0, -1}), plain.Le(Vec3f{1, 0, 0}));
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
  for (int k = 0; k < 200; ++k) {
    const Vec3f d = normalize(Vec3f{uni(rng), uni(rng), uni(rng)});
    const Vec3f r{d.z, d.y, -d.x};  // d turned by +90 degrees about +y
    EXPECT_NEAR(turned.pdf(r), plain.pdf(d), 1e-3f * plain.pdf(d)) << k;
  }
}

/// A white diffuse plane facing up under an image bright above the horizon
/// (a) and dim below (b): the plane sees the upper hemisphere only, so its
/// radiance is albedo * a, whatever b, under every strategy.
TEST(EnvironmentMap, ADiffusePlaneUnderATwoValuedImageRendersAlbedoTimesTheUpperValue) {
  auto image = std::make_shared<EnvironmentImage>();
  image->width = 16;
  image->height = 8;
  const float a = 0.8f, b = 5.0f;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) image->rgb.push_back(y < 4 ? a : b);
  Scene s;
  Material white;
  white.name = "white";
  white.albedo = {0.5f, 0.5f, 0.5f};
  s.materials.push_back(white);
  const float r = 1000;
  s.triangles.push_back(Triangle{{-r, 0, -r}, {-r, 0, r}, {r, 0, r}});
  s.triangles.push_back(Triangle{{-r, 0, -r}, {r, 0, r}, {r, 0, -r}});
  s.material_of = {0, 0};
  s.environment_image = image;
  s.environment = {0.5f * (a + b), 0.5f * (a + b), 0.5f * (a + b)};  // its mean over the sphere
  s.camera = CameraSpec{{0, 1, 0}, {0, 0, 0.001f}, {0, 0, 1}, 30.0f};
  s.width = s.height = 16;
  for (LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    RenderSettings settings;
    settings.spp = test::scaled(256, 32);
    settings.max_depth = 1;
    settings.light_sampling = strategy;
    const Film film = test::render_scene(s, settings, "grid");
    const test::ChannelStats st = test::channel_stats(film, 1);
    EXPECT_NEAR(st.mean, 0.5 * a, 4.0 * st.standard_error + 1e-4) << light_sampling_name(strategy);
  }
}

/// Radiance RGBE, flat scanlines: a w x h image of one colour.
void write_constant_hdr(const std::filesystem::path& file, int w, int h, std::uint8_t m, std::uint8_t e) {
  std::ofstream out(file, std::ios::binary);
  out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << h << " +X " << w << "\n";
  for (int i = 0; i < w * h; ++i) out << char(m) << char(m) << char(m) << char(e);
}

TEST(EnvironmentMap, AConstantImageIsLoadedAsTheConstantEnvironment) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kappa_env_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::filesystem::copy(test::assets_dir() / "cornell-box" / "cornell_box.obj", dir / "cornell_box.obj");
  write_constant_hdr(dir / "grey.hdr", 8, 4, 128, 128);
  test::write_file(dir / "scene.json", R"({"meshes": ["cornell_box.obj"], "environment": "grey.hdr"})");
  Warnings w;
  const Scene scene = load_scene(dir / "scene.json", w);
  EXPECT_EQ(scene.environment_image, nullptr);
  const std::vector<float> texels = image_library().read((dir / "grey.hdr").string(), 3);
  EXPECT_EQ(scene.environment, (Vec3f{texels[0], texels[1], texels[2]}));
  EXPECT_GT(scene.environment.x, 0.0f);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kappa
