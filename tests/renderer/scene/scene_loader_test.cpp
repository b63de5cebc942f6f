// scene.json and bare-OBJ scenes.
#include "renderer/scene/scene_loader.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace kappa {
namespace {

const char* kTriangle = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";

std::string error_of(const std::filesystem::path& file) {
  try {
    Warnings w;
    load_scene(file, w);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneLoader, ReadsEveryField) {
  test::TempDir dir;
  test::write_file(dir / "t.obj", kTriangle);
  test::write_file(dir / "scene.json", R"({"meshes": ["t.obj", "t.obj"],
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 30},
    "environment": [0.5, 1, 2], "film": {"width": 20, "height": 10}})");
  Warnings w;
  const Scene s = load_scene(dir / "scene.json", w);
  // The mesh listed twice loads twice, with a word: its emitters would count double.
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("is listed twice: its triangles, and any emitters, count twice"), std::string::npos) << w[0];
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.camera.eye, (Vec3f{0, 0, 5}));
  EXPECT_EQ(s.camera.vfov_deg, 30.0f);
  EXPECT_EQ(s.environment, (Vec3f{0.5f, 1, 2}));
  EXPECT_EQ(s.width, 20);
  EXPECT_EQ(s.height, 10);
  EXPECT_EQ(s.name, dir.path().filename().string());  // "scene.json" is named after its folder
}

TEST(SceneLoader, BareObjGetsAFramingCameraAndAWhiteSky) {
  test::TempDir dir;
  test::write_file(dir / "tri.obj", kTriangle);
  Warnings w;
  const Scene s = load_scene(dir / "tri.obj", w);
  EXPECT_EQ(s.name, "tri");
  EXPECT_EQ(s.environment, (Vec3f{1, 1, 1}));
  EXPECT_GT(s.camera.eye.z, 1.0f);  // in front of the triangle, looking at its centre
  EXPECT_NEAR(s.camera.look_at.y, 0.0f, 1e-6f);  // the bounding box centre
}

TEST(SceneLoader, FieldErrorsNameTheField) {
  test::TempDir dir;
  test::write_file(dir / "t.obj", kTriangle);
  const std::pair<const char*, const char*> cases[] = {
      {R"({"meshes": "t.obj"})", "'meshes'"},
      {R"({"meshes": []})", "'meshes'"},
      {R"({"meshes": ["t.obj"], "camera": {"eye": [0, 0], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 30}})",
       "'camera.eye'"},
      {R"({"meshes": ["t.obj"], "camera": {"eye": [0, 0, 1], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 180}})",
       "'camera.vfov_deg'"},
      {R"({"meshes": ["t.obj"], "camera": {"eye": [0, 0, 1], "look_at": [0, 0, 1], "up": [0, 1, 0], "vfov_deg": 30}})",
       "same point"},
      {R"({"meshes": ["t.obj"], "camera": {"eye": [0, 1, 0], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 30}})",
       "parallel"},
      {R"({"meshes": ["t.obj"], "environment": [1, -1, 1]})", "'environment'"},
      {R"({"meshes": ["t.obj"], "film": {"width": 0, "height": 5}})", "'film.width'"},
      {R"({"meshes": ["t.obj"], "film": {"width": 5, "height": 2.5}})", "'film.height'"},
      {R"({"meshes": ["missing.obj"]})", "missing.obj"},
      {R"([1, 2])", "JSON object"},
  };
  for (const auto& [json, expected] : cases) {
    test::write_file(dir / "s.json", json);
    EXPECT_NE(error_of(dir / "s.json").find(expected), std::string::npos) << json << " -> " << error_of(dir / "s.json");
  }
}

TEST(SceneLoader, SyntaxErrorsGiveLineAndColumn) {
  test::TempDir dir;
  test::write_file(dir / "s.json", "{\n  \"meshes\": [\"t.obj\"]\n  \"film\": {}\n}\n");
  EXPECT_NE(error_of(dir / "s.json").find("s.json:3:"), std::string::npos) << error_of(dir / "s.json");
}

TEST(SceneLoader, UnknownFieldsWarn) {
  test::TempDir dir;
  test::write_file(dir / "t.obj", kTriangle);
  test::write_file(dir / "s.json", R"({"meshes": ["t.obj"], "integrator": "bdpt"})");
  Warnings w;
  load_scene(dir / "s.json", w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("integrator"), std::string::npos);
}

TEST(SceneLoader, UnsupportedExtensionIsRefused) {
  test::TempDir dir;
  test::write_file(dir / "model.ply", "ply\n");
  EXPECT_NE(error_of(dir / "model.ply").find("unsupported scene format"), std::string::npos);
}

TEST(SceneLoader, SharedScenesLoad) {
  const auto shared = test::shared_scenes_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/scenes not present (a user's clone): skipping the shared scenes";
  for (const char* name : {"bunny/scene_lowres.json", "sponza/scene.json", "teapot-in-stadium/scene.json"}) {
    Warnings w;
    const Scene s = load_scene(shared / name, w);
    // Sponza's one zero-area triangle (documented in the scenes' README) is the only expected warning.
    for (const auto& warning : w) EXPECT_NE(warning.find("1 zero-area triangles dropped"), std::string::npos) << warning;
    EXPECT_GT(s.triangles.size(), 1000u) << name;
  }
}

// Numbers are never silently changed: a number that overflows a double was
// an internal error without the file's name, and a duplicate key silently
// took its last value. Both are refused with file:line; strings holding
// braces, colons or escaped quotes do not confuse the check.
TEST(SceneLoader, OverflowingNumbersAndDuplicateKeysAreRefusedWithTheirLine) {
  test::TempDir dir;
  test::write_file(dir / "t.obj", kTriangle);
  test::write_file(dir / "over.json", "{\"meshes\": [\"t.obj\"],\n \"environment\": [1, -1e400, 1]}\n");
  EXPECT_NE(error_of(dir / "over.json").find("over.json:2: number '-1e400' does not fit a double"), std::string::npos)
      << error_of(dir / "over.json");
  test::write_file(dir / "dup.json", "{\"meshes\": [\"t.obj\"],\n \"environment\": [1, 1, 1],\n \"environment\": [0, 0, 0]}\n");
  EXPECT_NE(error_of(dir / "dup.json").find("dup.json:3: key 'environment' appears twice"), std::string::npos)
      << error_of(dir / "dup.json");
  test::write_file(dir / "nested.json",
                   "{\"meshes\": [\"t.obj\"], \"camera\": {\"eye\": [0, 0, 5],\n \"look_at\": [0, 0, 0], \"eye\": [0, 0, 4]}}\n");
  EXPECT_NE(error_of(dir / "nested.json").find("nested.json:2: key 'eye' appears twice"), std::string::npos)
      << error_of(dir / "nested.json");
  // The same key in two different objects, and keys inside strings, are fine.
  test::write_file(dir / "fine.json",
                   "{\"meshes\": [\"t.obj\"], \"film\": {\"width\": 8, \"height\": 8},\n"
                   " \"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0], \"vfov_deg\": 30},\n"
                   " \"note {\\\"film\\\": 1}\": \"a: {\\\"width\\\": 2}\"}\n");
  Warnings w;
  EXPECT_NO_THROW(load_scene(dir / "fine.json", w)) << error_of(dir / "fine.json");
}

// Limits said right: a finite value past Kappa's limit says the limit, not
// "finite".
TEST(SceneLoader, ValuesPastTheCoordinateLimitSayTheLimit) {
  test::TempDir dir;
  test::write_file(dir / "t.obj", kTriangle);
  test::write_file(dir / "big.json", R"({"meshes": ["t.obj"], "environment": [1, 1e13, 1]})");
  EXPECT_NE(error_of(dir / "big.json").find("field 'environment': 10000000000000.0 exceeds Kappa's limit of 1e+12"),
            std::string::npos)
      << error_of(dir / "big.json");
}

}  // namespace
}  // namespace kappa
