// The samplers: where each dimension's samples fall. Sobol's first 2^m
// samples of a pixel form a (0,m,2)-net on every pair of dimensions a path
// reads (and stratify every 1D one); the stratified sampler puts one sample
// in each stratum; each is the same for any thread count.
#include <gtest/gtest.h>

#include <cstring>
#include <set>

#include "core/input_error.h"
#include "core/thread_limit.h"
#include "renderer/render/render_helpers.h"
#include "renderer/render/samplers.h"
#include "renderer/scene/scene_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

namespace dims = path_dimensions;

/// Whether the points form a (0,m,2)-net: for every split of 2^m into
/// 2^a x 2^(m-a) boxes, one point in each.
bool is_net(const std::vector<std::pair<float, float>>& points, int m) {
  for (int a = 0; a <= m; ++a) {
    const std::uint32_t nx = 1u << a, ny = 1u << (m - a);
    std::set<std::uint64_t> seen;
    for (const auto& [x, y] : points) {
      const auto i = std::uint64_t(double(x) * nx), j = std::uint64_t(double(y) * ny);
      if (!seen.insert(j * nx + i).second) return false;
    }
  }
  return true;
}

/// One point in each of the n intervals of [0, 1).
bool stratifies(const std::vector<float>& values, std::uint32_t n) {
  std::set<std::uint64_t> seen;
  for (float v : values)
    if (!seen.insert(std::uint64_t(double(v) * n)).second) return false;
  return seen.size() == n;
}

template <class Sampler>
std::vector<std::pair<float, float>> points2d(std::uint64_t pixel, std::uint32_t dimension, std::uint32_t n,
                                              std::uint32_t first = 0) {
  std::vector<std::pair<float, float>> out;
  for (std::uint32_t i = first; i < first + n; ++i) out.push_back(Sampler(7, pixel, i, n).get2D(dimension));
  return out;
}

template <class Sampler>
std::vector<float> points1d(std::uint64_t pixel, std::uint32_t dimension, std::uint32_t n) {
  std::vector<float> out;
  for (std::uint32_t i = 0; i < n; ++i) out.push_back(Sampler(7, pixel, i, n).get1D(dimension));
  return out;
}

TEST(Samplers, SobolFirstPowersOfTwoAreNetsOnEveryPairAPathReads) {
  for (std::uint64_t pixel : {0ull, 1ull, 4242ull}) {
    for (int m = 0; m <= 10; ++m) {
      const std::uint32_t n = 1u << m;
      SCOPED_TRACE("pixel " + std::to_string(pixel) + ", 2^" + std::to_string(m) + " samples");
      EXPECT_TRUE(is_net(points2d<SobolSampler>(pixel, dims::kPixel, n), m)) << "pixel position";
      for (int bounce : {0, 1, 2}) {
        EXPECT_TRUE(is_net(points2d<SobolSampler>(pixel, dims::light_point(bounce), n), m)) << "light, bounce " << bounce;
        EXPECT_TRUE(is_net(points2d<SobolSampler>(pixel, dims::bsdf(bounce), n), m)) << "BSDF, bounce " << bounce;
        EXPECT_TRUE(stratifies(points1d<SobolSampler>(pixel, dims::light_choice(bounce), n), n)) << "light choice";
        EXPECT_TRUE(stratifies(points1d<SobolSampler>(pixel, dims::roulette(bounce), n), n)) << "roulette";
      }
    }
    // The next 2^m samples are a net too: a render continued in passes
    // keeps its stratification.
    EXPECT_TRUE(is_net(points2d<SobolSampler>(pixel, dims::bsdf(1), 64, 64), 6));
  }
}

// The byte tables give the generator matrix's sums exactly (the image of a
// sobol render must not change with how they are computed).
TEST(Samplers, SobolSecondDimensionByTableIsTheBitwiseSum) {
  std::uint64_t x = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < 100000; ++i) {
    x = mix64(x);
    const std::uint32_t index = std::uint32_t(x);
    ASSERT_EQ(sobol_dimension1(index), sobol_dimension1_bitwise(index)) << index;
  }
  for (std::uint32_t index : {0u, 1u, 2u, 3u, 0xFFFFFFFFu, 0x80000000u})
    EXPECT_EQ(sobol_dimension1(index), sobol_dimension1_bitwise(index)) << index;
}

TEST(Samplers, SobolDimensionPairsAreDecorrelated) {
  // The same sample's pixel position and BSDF direction come from differently
  // shuffled orders: their first coordinates do not move together.
  double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
  const std::uint32_t n = 1024;
  for (std::uint32_t i = 0; i < n; ++i) {
    SobolSampler s(3, 99, i, n);
    const double x = s.get2D(dims::kPixel).first, y = s.get2D(dims::bsdf(0)).first;
    sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
  }
  const double cov = sxy / n - sx / n * sy / n;
  const double r = cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  EXPECT_LT(std::abs(r), 0.15) << "correlation " << r;
  // And a pixel's samples differ from its neighbour's.
  EXPECT_NE(SobolSampler(3, 99, 0, n).get2D(dims::kPixel), SobolSampler(3, 100, 0, n).get2D(dims::kPixel));
}

TEST(Samplers, StratifiedPutsOneSampleInEachStratum) {
  for (std::uint32_t spp : {1u, 4u, 12u, 16u, 17u, 64u}) {
    SCOPED_TRACE(std::to_string(spp) + " spp");
    for (std::uint32_t d : {dims::light_choice(0), dims::roulette(1)})
      EXPECT_TRUE(stratifies(points1d<StratifiedSampler>(5, d, spp), spp));
    std::uint32_t nx = std::uint32_t(std::sqrt(double(spp)));
    while (nx > 1 && spp % nx != 0) --nx;
    const std::uint32_t ny = spp / nx;
    for (std::uint32_t d : {dims::kPixel, dims::bsdf(0), dims::light_point(2)}) {
      std::set<std::uint64_t> cells;
      for (const auto& [x, y] : points2d<StratifiedSampler>(5, d, spp)) {
        ASSERT_TRUE(x >= 0 && x < 1 && y >= 0 && y < 1);
        cells.insert(std::uint64_t(double(y) * ny) * nx + std::uint64_t(double(x) * nx));
      }
      EXPECT_EQ(cells.size(), spp) << "dimension " << d;
    }
  }
}

TEST(Samplers, EverySamplerIsTheSameImageAtAnyThreadCount) {
  Warnings warnings;
  Scene scene = load_scene(test::assets_dir() / "cornell-box" / "scene.json", warnings);
  scene.width = scene.height = 32;
  std::vector<std::vector<float>> images;
  for (SamplerKind k : {SamplerKind::independent, SamplerKind::stratified, SamplerKind::sobol}) {
    RenderSettings settings;
    settings.spp = 8;
    settings.sampler = k;
    const auto on = [&](int threads) {
      const ThreadLimit limit(threads);
      return test::render_scene(scene, settings, "grid").rgb;
    };
    const std::vector<float> one = on(1);
    EXPECT_EQ(std::memcmp(one.data(), on(2).data(), one.size() * sizeof(float)), 0) << sampler_name(k);
    images.push_back(one);
  }
  // And the samplers do differ.
  EXPECT_NE(images[0], images[1]);
  EXPECT_NE(images[0], images[2]);
}

TEST(Samplers, NamesRoundTripAndOnlyStratifiedNeedsTheTotal) {
  for (SamplerKind k : {SamplerKind::independent, SamplerKind::stratified, SamplerKind::sobol})
    EXPECT_EQ(parse_sampler(sampler_name(k)), k);
  EXPECT_THROW(parse_sampler("halton"), InputError);
  EXPECT_TRUE(needs_total(SamplerKind::stratified));
  EXPECT_FALSE(needs_total(SamplerKind::sobol));
  EXPECT_FALSE(needs_total(SamplerKind::independent));
}

}  // namespace
}  // namespace kappa
