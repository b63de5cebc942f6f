// glTF scenes through the command line: the same triangles and materials as
// OBJ and as glTF (.gltf with a .bin, .glb, data URIs) render bitwise the
// same image; the report names the glTF file and its counts; --camera picks
// a glTF camera by name or index and its aspect sets the film; a bad glTF
// file is one line with exit 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "image_files.h"
#include "test_util.h"

namespace kappa {
namespace {

std::filesystem::path gltf_dir() { return test::assets_dir() / "gltf"; }

struct Rendered {
  test::ExrFile image;
  nlohmann::json report;
  std::string std_err;
};

Rendered render(const std::filesystem::path& scene, const std::vector<std::string>& extra = {}) {
  test::TempDir tmp;
  std::vector<std::string> args = {"render", scene.string(), "--spp", "4", "--out", (tmp / "o.exr").string(),
                                   "--report", (tmp / "r.json").string(), "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = test::run_kappa(args);
  EXPECT_EQ(r.exit_code, 0) << r.std_err;
  Rendered out;
  out.std_err = r.std_err;
  if (r.exit_code != 0) return out;
  out.image = test::read_exr_file(tmp / "o.exr");
  out.report = nlohmann::json::parse(test::read_file(tmp / "r.json"));
  return out;
}

TEST(GltfCli, TheSameTrianglesAsObjAndAsGltfRenderBitwiseTheSameImage) {
  const Rendered obj = render(gltf_dir() / "twin_obj.json");
  const Rendered gltf = render(gltf_dir() / "twin_gltf.json");
  ASSERT_FALSE(obj.image.pixels.empty());
  EXPECT_TRUE(test::bitwise_equal(obj.image.pixels, gltf.image.pixels));
  // Bare files too (environment 1, the framing camera), every container.
  const Rendered bare_obj = render(gltf_dir() / "twin.obj", {"--width", "24", "--height", "16"});
  for (const char* f : {"twin.gltf", "twin.glb", "twin_embedded.gltf"}) {
    const Rendered bare = render(gltf_dir() / f, {"--width", "24", "--height", "16"});
    EXPECT_TRUE(test::bitwise_equal(bare_obj.image.pixels, bare.image.pixels)) << f;
  }
}

TEST(GltfCli, TheReportNamesTheGltfFileAndItsCounts) {
  const Rendered r = render(gltf_dir() / "primitives.gltf", {"--width", "16", "--height", "16"});
  EXPECT_EQ(r.report["schema_version"], 17);
  ASSERT_EQ(r.report["gltf"].size(), 1u);
  const nlohmann::json& g = r.report["gltf"][0];
  EXPECT_NE(g["file"].get<std::string>().find("primitives.gltf"), std::string::npos);
  EXPECT_EQ(g["triangles"], 10);  // the shared mesh copied for its two nodes
  EXPECT_EQ(g["mesh_instances"], 5);  // gen.py: four meshes, the shared one placed twice
  EXPECT_EQ(r.report["punctual_lights"], 0);
  // An OBJ scene has none.
  EXPECT_TRUE(render(gltf_dir() / "twin.obj", {"--width", "8", "--height", "8"}).report["gltf"].empty());
}

TEST(GltfCli, CameraPicksAGltfCameraByNameOrIndexAndItsAspectSetsTheFilm) {
  const Rendered first = render(gltf_dir() / "cameras.gltf", {"--spp", "1"});
  EXPECT_EQ(first.image.width, 512);
  EXPECT_EQ(first.image.height, 256);  // "wide": aspect 2
  EXPECT_EQ(first.report["camera"]["name"], "wide");
  EXPECT_EQ(first.report["camera"]["index"], 1);  // its index in the file's cameras (0 is orthographic)
  const Rendered tele = render(gltf_dir() / "cameras.gltf", {"--camera", "tele", "--width", "20", "--height", "10"});
  EXPECT_EQ(tele.report["camera"]["name"], "tele");
  EXPECT_EQ(tele.image.width, 20);
  const Rendered by_index = render(gltf_dir() / "cameras.gltf", {"--camera", "2", "--width", "20", "--height", "10"});
  EXPECT_EQ(by_index.report["camera"]["name"], "tele");
  EXPECT_TRUE(test::bitwise_equal(tele.image.pixels, by_index.image.pixels));
  // One side given: the other from the camera's aspect.
  const Rendered one_side = render(gltf_dir() / "cameras.gltf", {"--width", "64", "--spp", "1"});
  EXPECT_EQ(one_side.image.height, 32);

  test::TempDir tmp;
  const auto bad = test::run_kappa({"render", (gltf_dir() / "cameras.gltf").string(), "--camera", "nope", "--out",
                                    (tmp / "o.exr").string()});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.std_err.find("no perspective camera of that name or index"), std::string::npos) << bad.std_err;
  EXPECT_NE(bad.std_err.find("1 'wide'"), std::string::npos) << bad.std_err;
  EXPECT_FALSE(std::filesystem::exists(tmp / "o.exr"));
}

TEST(GltfCli, AMaskMaterialIsCutOutWhereItsAlphaIsBelowTheCutoffInGridGrid2AndEmbree) {
  // mask.glb: a 2 x 2 quad at z = 0 whose texture is opaque in its left half
  // (alpha 255) and transparent in its right (alpha 0); seen head-on, filling
  // the middle of the film. The first hit's albedo is the quad's (1) where it
  // is opaque, 0 where the ray passes through into the empty world.
  test::TempDir tmp;
  test::write_file(tmp / "scene.json",
                   nlohmann::json{{"meshes", {(gltf_dir() / "mask.glb").string()}},
                                  {"camera", {{"eye", {0, 0, 4}}, {"look_at", {0, 0, 0}}, {"up", {0, 1, 0}},
                                              {"vfov_deg", 20}}},
                                  {"film", {{"width", 16}, {"height", 16}}}}
                       .dump());
  // Not naive here: under the ASan build (GCC 12), LeakSanitizer's tracer
  // crashes at exit on a garbage dynamic-TLS entry for this run with naive
  // and 2 spp or more (a tool fault, reproduced, no leak). Naive's cut-outs
  // are checked in-process (Cutouts.*).
  for (const char* accel : {"grid", "grid2", "embree"}) {
    const Rendered r = render(tmp / "scene.json", {"--aov", "albedo", "--accel", accel});
    const int g = r.image.channel("albedo.G");
    ASSERT_GE(g, 0);
    const std::size_t stride = r.image.channels.size();
    auto albedo = [&](int x, int y) { return r.image.pixels[(std::size_t(y) * 16 + std::size_t(x)) * stride + std::size_t(g)]; };
    // Rows through the quad's middle: columns 5-6 lie on its left half, 9-10 on its right.
    for (int y = 6; y <= 9; ++y) {
      for (int x : {5, 6}) EXPECT_GT(albedo(x, y), 0.9f) << accel << " " << x << "," << y;
      for (int x : {9, 10}) EXPECT_EQ(albedo(x, y), 0.0f) << accel << " " << x << "," << y;
    }
    EXPECT_GT(r.report["rays"]["camera"]["alpha_tests"].get<long>(), 0) << accel;
  }
}

TEST(GltfCli, ABadGltfFileIsOneLineWithExitTwo) {
  test::TempDir tmp;
  test::write_file(tmp / "bad.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "../x.bin", "byteLength": 4}]})");
  const auto r = test::run_kappa({"render", (tmp / "bad.gltf").string(), "--out", (tmp / "o.exr").string()});
  EXPECT_EQ(r.exit_code, 2);
  ASSERT_EQ(r.err_lines().size(), 1u) << r.std_err;
  EXPECT_NE(r.std_err.find("bad.gltf: /buffers/0/uri:"), std::string::npos) << r.std_err;
  EXPECT_NE(r.std_err.find("leaves the glTF file's folder"), std::string::npos) << r.std_err;
}

}  // namespace
}  // namespace kappa
