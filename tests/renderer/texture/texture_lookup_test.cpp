// Texture lookups through the OpenImageIO module: the texel a coordinate
// names (nearest, and bilinear at texel centres and between two), repeat
// wrapping, sRGB decoding of 8-bit colour maps, (u, v) placement by -s and
// -o, and the camera-ray footprint in (u, v).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "renderer/image/image_library.h"
#include "renderer/render/lights.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/texture/texture_lookup.h"
#include "renderer/texture/uv_footprint.h"
#include "test_util.h"

namespace kappa {
namespace {

/// A 4 x 2 grey image, texel (x, y) = 10 + 30 x + 100 y (of 255).
std::filesystem::path write_ramp(const std::filesystem::path& dir) {
  std::vector<std::uint8_t> pixels;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) pixels.push_back(std::uint8_t(10 + 30 * x + 100 * y));
  const std::filesystem::path file = dir / "ramp.png";
  image_library().write_8bit(file.string(), 4, 2, 1, pixels);
  return file;
}

float texel(int x, int y) { return float(10 + 30 * x + 100 * y) / 255.0f; }

class TextureLookup : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = std::filesystem::temp_directory_path() / ("kappa_texture_" + std::to_string(::getpid()));
    std::filesystem::create_directories(m_dir);
    m_file = write_ramp(m_dir);
    m_handle = image_library().texture(m_file.string());
  }
  void TearDown() override { std::filesystem::remove_all(m_dir); }

  float at(TextureFilter filter, float s, float t) const {
    TextureCoords c;
    c.s = s;
    c.t = t;
    float out = -1;
    EXPECT_TRUE(image_library().lookup(m_handle, TextureWrap::periodic, TextureWrap::periodic, filter, 0, 1, c, &out));
    return out;
  }

  std::filesystem::path m_dir, m_file;
  void* m_handle = nullptr;
};

TEST_F(TextureLookup, TheFileIsReadAsWritten) {
  const ImageFacts f = image_library().inspect(m_file.string());
  EXPECT_EQ(f.width, 4);
  EXPECT_EQ(f.height, 2);
  EXPECT_EQ(f.channels, 1);
  EXPECT_FALSE(f.alpha);
  EXPECT_FALSE(f.floating);
  const std::vector<float> all = image_library().read(m_file.string(), 1);
  ASSERT_EQ(all.size(), 8u);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_FLOAT_EQ(all[std::size_t(y * 4 + x)], texel(x, y)) << x << " " << y;
}

TEST_F(TextureLookup, NearestAndBilinearReturnTheTexelAtItsCentre) {
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const float s = (float(x) + 0.5f) / 4.0f, t = (float(y) + 0.5f) / 2.0f;
      EXPECT_NEAR(at(TextureFilter::nearest, s, t), texel(x, y), 1e-6f) << x << " " << y;
      EXPECT_NEAR(at(TextureFilter::filtered, s, t), texel(x, y), 1e-5f) << x << " " << y;
      // Anywhere inside the texel, nearest is still the texel.
      EXPECT_NEAR(at(TextureFilter::nearest, s + 0.1f, t - 0.2f), texel(x, y), 1e-6f) << x << " " << y;
    }
}

TEST_F(TextureLookup, BilinearIsTheMeanHalfwayBetweenTwoTexels) {
  EXPECT_NEAR(at(TextureFilter::filtered, 0.5f, 0.25f), 0.5f * (texel(1, 0) + texel(2, 0)), 1e-5f);
  EXPECT_NEAR(at(TextureFilter::filtered, 0.375f, 0.5f), 0.5f * (texel(1, 0) + texel(1, 1)), 1e-5f);
}

TEST_F(TextureLookup, CoordinatesRepeat) {
  for (float k : {-2.0f, -1.0f, 1.0f, 3.0f})
    EXPECT_NEAR(at(TextureFilter::nearest, 0.625f + k, 0.75f + k), texel(2, 1), 1e-6f) << k;
}

TEST_F(TextureLookup, ColourMapsAreDecodedFromSrgbAndPlacedByScaleAndOffset) {
  TextureMap map;
  map.handle = m_handle;
  map.channels = 1;
  map.srgb = true;
  // (u, v) = (0.875, 0.25): t = 1 - v = 0.75, texel (3, 1).
  const Vec3f c = lookup_colour(map, Vec2f{0.875f, 0.25f}, UvFootprint{}, 1.0f);
  const float expected = srgb_to_linear(texel(3, 1));
  EXPECT_NEAR(c.x, expected, 2e-5f);
  EXPECT_EQ(c.x, c.y);  // a grey file's one channel, repeated
  EXPECT_EQ(c.x, c.z);
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.21404f, 1e-5f);
  map.srgb = false;
  EXPECT_NEAR(lookup_colour(map, Vec2f{0.875f, 0.25f}, UvFootprint{}, 1.0f).x, texel(3, 1), 1e-5f);
  // -s 2 1 -o 0.25 0: u = 0.3125 reads s = 0.875 (texel 3's centre), u =
  // 0.0625 reads s = 0.375 (texel 1's).
  map.scale = {2, 1};
  map.offset = {0.25f, 0};
  EXPECT_NEAR(lookup_colour(map, Vec2f{0.3125f, 0.25f}, UvFootprint{}, 1.0f).x, texel(3, 1), 1e-5f);
  EXPECT_NEAR(lookup_colour(map, Vec2f{0.0625f, 0.25f}, UvFootprint{}, 1.0f).x, texel(1, 1), 1e-5f);
}

TEST(UvFootprint, APlaneWithUvFromXyMovesOneUnitOfUPerUnitOfX) {
  const Triangle tri{{0, 0, 0}, {2, 0, 0}, {0, 4, 0}};
  const TriangleUVs uvs{{{0, 0}, {1, 0}, {0, 1}}};  // u = x / 2, v = y / 4
  const UvFootprint f = uv_footprint(tri, uvs, Vec3f{1, 0, 0}, Vec3f{0, 2, 0});
  EXPECT_NEAR(f.dudx, 0.5f, 1e-6f);
  EXPECT_NEAR(f.dvdx, 0.0f, 1e-6f);
  EXPECT_NEAR(f.dudy, 0.0f, 1e-6f);
  EXPECT_NEAR(f.dvdy, 0.5f, 1e-6f);
  const TriangleUVs flat{{{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}}};  // degenerate: no footprint
  const UvFootprint none = uv_footprint(tri, flat, Vec3f{1, 0, 0}, Vec3f{0, 2, 0});
  EXPECT_EQ(none.dudx, 0.0f);
  EXPECT_EQ(none.dvdy, 0.0f);
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

/// map_Ke replaces Ke (Blender): the triangle is a light even with Ke 0, its
/// power from the map's mean decoded texel, its radiance the texel at (u, v).
TEST(EmissionMap, ReplacesKeAndMakesTheTriangleALightOfItsMeanPower) {
  test::TempDir dir;
  std::vector<std::uint8_t> pixels = {0, 64, 128, 255};  // 4 x 1, grey
  image_library().write_8bit((dir / "glow.png").string(), 4, 1, 1, pixels);
  test::write_file(dir / "q.obj",
                   "mtllib q.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                   "usemtl glow\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  test::write_file(dir / "q.mtl", "newmtl glow\nKd 0 0 0\nKe 0 0 0\nmap_Ke glow.png\n");
  Warnings w;
  const Scene scene = load_scene(dir / "q.obj", w);
  ASSERT_EQ(scene.texture_maps.size(), 1u);
  const Material& m = scene.materials[scene.material_of[0]];
  EXPECT_TRUE(m.emissive());
  EXPECT_FALSE(m.lambertian());
  double mean = 0;
  for (std::uint8_t p : pixels) mean += srgb_to_linear(float(p) / 255.0f) / 4.0;
  EXPECT_NEAR(scene.texture_maps[0].mean.x, mean, 1e-6);
  const Lights lights(scene);
  EXPECT_EQ(lights.triangle_count(), 2u);
  for (int x = 0; x < 4; ++x)
    EXPECT_NEAR(emitted(scene, m, Vec2f{(float(x) + 0.5f) / 4.0f, 0.5f}).y, srgb_to_linear(float(pixels[std::size_t(x)]) / 255.0f),
                2e-5f)
        << x;
}

}  // namespace
}  // namespace kappa
