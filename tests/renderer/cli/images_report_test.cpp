// The report's `images` section: an untextured render never loads the
// OpenImageIO module (module_loaded false: what keeps its start-up as
// before), a textured one does and reports the texture cache's statistics,
// and its cut-out lookups are counted per class as alpha tests.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "image_files.h"
#include "renderer/io/preview.h"
#include "test_util.h"

namespace kappa {
namespace {

nlohmann::json render_report(const std::filesystem::path& scene, const std::vector<std::string>& extra = {}) {
  test::TempDir tmp;
  std::vector<std::string> args = {"render", scene.string(), "--spp", "2", "--width", "32", "--height", "32",
                                   "--out", (tmp / "o.exr").string(), "--report", (tmp / "r.json").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = test::run_kappa(args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  return nlohmann::json::parse(test::read_file(tmp / "r.json"));
}

TEST(ImagesReport, AnUntexturedRenderNeverLoadsOpenImageIo) {
  const nlohmann::json j = render_report(test::assets_dir() / "cornell-box" / "scene.json");
  EXPECT_EQ(j["schema_version"], 17);
  EXPECT_EQ(j["images"]["module_loaded"], false);
  EXPECT_EQ(j["images"]["texture_maps"], 0);
  EXPECT_TRUE(j["images"]["texture_cache"].is_null());
  EXPECT_EQ(j["rays"]["shadow"]["alpha_tests"], 0);
}

TEST(ImagesReport, ATexturedRenderReportsItsMapsCacheAndAlphaTests) {
  for (const char* accel : {"grid", "grid2", "naive", "embree"}) {
    const nlohmann::json j = render_report(test::assets_dir() / "textured-box" / "scene.json", {"--accel", accel});
    EXPECT_EQ(j["images"]["module_loaded"], true) << accel;
    EXPECT_EQ(j["images"]["texture_maps"], 5) << accel;
    EXPECT_EQ(j["images"]["opacity_masks"], 1) << accel;
    const nlohmann::json& cache = j["images"]["texture_cache"];
    ASSERT_TRUE(cache.is_object()) << accel;
    EXPECT_GT(cache["tile_lookups"].get<double>(), 0) << accel;
    EXPECT_GT(cache["hit_rate"].get<double>(), 0.5) << accel;
    EXPECT_LE(cache["hit_rate"].get<double>(), 1.0) << accel;
    // The card is in view and between the floor and the light: camera and
    // shadow rays test its opacity.
    EXPECT_GT(j["rays"]["camera"]["alpha_tests"].get<double>(), 0) << accel;
    EXPECT_GT(j["rays"]["shadow"]["alpha_tests"].get<double>(), 0) << accel;
    EXPECT_NE(j["render"]["path_variant"].get<std::string>().find(", extras"), std::string::npos) << accel;
  }
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

/// --preview: the render's RGB as 8-bit sRGB beside the EXR, scaled by
/// 2^EV and clipped; a name OpenImageIO cannot write is refused before the
/// render, and a preview over an input is refused like any output.
TEST(Preview, IsTheExrScaledClippedAndSrgbEncoded) {
  test::TempDir tmp;
  const std::string scene = (test::assets_dir() / "cornell-box" / "scene.json").string();
  const auto r = test::run_kappa({"render", scene, "--spp", "2", "--width", "24", "--height", "16", "--out",
                                  (tmp / "o.exr").string(), "--preview", (tmp / "p.png").string(),
                                  "--preview-exposure", "1", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.std_err;
  const test::ExrFile exr = test::read_exr_file(tmp / "o.exr");
  const test::PngFile png = test::read_png_file(tmp / "p.png");
  ASSERT_EQ(png.width, 24);
  ASSERT_EQ(png.height, 16);
  const std::vector<float> red = exr.values("R"), green = exr.values("G");
  int clipped = 0;
  for (std::size_t i = 0; i < red.size(); ++i) {
    EXPECT_EQ(png.rgb[3 * i], preview_byte(red[i], 2.0f)) << i;
    EXPECT_EQ(png.rgb[3 * i + 1], preview_byte(green[i], 2.0f)) << i;
    clipped += png.rgb[3 * i] == 255;
  }
  EXPECT_GT(clipped, 0);  // the light, at least
  EXPECT_EQ(preview_byte(0.5f, 1.0f), 188);  // the sRGB code of linear 0.5
  EXPECT_EQ(preview_byte(NAN, 1.0f), 0);

  const auto bad = test::run_kappa({"render", scene, "--spp", "1", "--out", (tmp / "q.exr").string(), "--preview",
                                    (tmp / "p.gif").string(), "--quiet"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.std_err.find("--preview"), std::string::npos) << bad.std_err;
  EXPECT_FALSE(std::filesystem::exists(tmp / "q.exr"));
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

/// cast, bench and sweep cast rays against the triangles alone: on a scene
/// with cut-outs they say so rather than measure other rays without a word.
TEST(Cutouts, CastSaysItsRaysIgnoreTheCutOuts) {
  test::TempDir tmp;
  const auto r = test::run_kappa({"cast", (test::assets_dir() / "textured-box" / "scene.json").string(), "--rays",
                                  "lines", "--n", "1000", "--report", (tmp / "c.json").string()});
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  EXPECT_NE(r.std_err.find("cut-outs are not applied by kappa cast"), std::string::npos) << r.std_err;
  const auto plain = test::run_kappa({"cast", (test::assets_dir() / "cornell-box" / "scene.json").string(), "--rays",
                                      "lines", "--n", "1000", "--report", (tmp / "d.json").string()});
  EXPECT_EQ(plain.std_err.find("cut-outs"), std::string::npos) << plain.std_err;
}

}  // namespace
}  // namespace kappa
