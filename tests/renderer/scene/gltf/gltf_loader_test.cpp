// glTF 2.0 loading on the generated scenes of assets/gltf (gen.py's docstring states each one's content).
#include "renderer/scene/scene_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "test_util.h"

namespace kappa {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::filesystem::path gltf_dir() { return test::assets_dir() / "gltf"; }

Scene load(const std::string& name, Warnings& warnings) { return load_scene(gltf_dir() / name, warnings); }

std::string str(const Vec3f& v) {
  return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

void expect_near(const Vec3f& got, const Vec3f& want, double tolerance, const std::string& what) {
  EXPECT_NEAR(got.x, want.x, tolerance) << what << ": " << str(got) << " vs " << str(want);
  EXPECT_NEAR(got.y, want.y, tolerance) << what << ": " << str(got) << " vs " << str(want);
  EXPECT_NEAR(got.z, want.z, tolerance) << what << ": " << str(got) << " vs " << str(want);
}

/// How many warnings hold `text`.
std::size_t warnings_with(const Warnings& warnings, const std::string& text) {
  return std::size_t(std::count_if(warnings.begin(), warnings.end(),
                                   [&](const std::string& w) { return w.find(text) != std::string::npos; }));
}

/// The one warning holding `text` (empty if none or several).
std::string warning_with(const Warnings& warnings, const std::string& text) {
  std::string found;
  for (const std::string& w : warnings)
    if (w.find(text) != std::string::npos) {
      if (!found.empty()) return "";
      found = w;
    }
  return found;
}

std::string all(const Warnings& warnings) {
  std::string s;
  for (const std::string& w : warnings) s += "\n  " + w;
  return s;
}

/// The parameters TwinReadsAlike compares, bit for bit; empty when equal.
std::string material_difference(const Material& a, const Material& b) {
  std::string d;
  if (!(a.albedo == b.albedo)) d += " albedo " + str(a.albedo) + " vs " + str(b.albedo);
  if (!(a.emission == b.emission)) d += " emission " + str(a.emission) + " vs " + str(b.emission);
  auto scalar = [&](const char* name, float x, float y) {
    if (!(x == y)) d += std::string(" ") + name + " " + std::to_string(x) + " vs " + std::to_string(y);
  };
  scalar("roughness", a.roughness, b.roughness);
  scalar("metallic", a.metallic, b.metallic);
  scalar("specular", a.specular, b.specular);
  scalar("ior", a.ior, b.ior);
  scalar("transmission", a.transmission, b.transmission);
  return d;
}

const Material& material_of(const Scene& s, std::size_t triangle) { return s.materials[s.material_of[triangle]]; }

const TextureMap& map_of(const Scene& s, const Material& m, MapSlot slot) {
  return s.texture_maps[std::size_t(m.maps[std::size_t(slot)])];
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec);
}

// A node's TRS (with a quaternion) over a child's column-major matrix: every
// world vertex as gen.py computed outer * inner * p in double, in index order.
TEST(GltfLoader, NestedTransforms) {
  Warnings w;
  const Scene s = load("nested_cube.gltf", w);
  const nlohmann::json expected = nlohmann::json::parse(test::read_file(gltf_dir() / "nested_cube_expected.json"));
  const nlohmann::json& triangles = expected.at("triangles");
  ASSERT_EQ(triangles.size(), 12u);
  ASSERT_EQ(s.triangles.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t) {
    const Vec3f got[3] = {s.triangles[t].v0, s.triangles[t].v1, s.triangles[t].v2};
    for (std::size_t k = 0; k < 3; ++k) {
      const nlohmann::json& p = triangles[t][k];
      expect_near(got[k], Vec3f{float(p[0].get<double>()), float(p[1].get<double>()), float(p[2].get<double>())},
                  1e-5, "triangle " + std::to_string(t) + " vertex " + std::to_string(k));
    }
  }
  // No material: the specification's default (base colour 1, metallic 1, roughness 1).
  ASSERT_EQ(s.material_of.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t) {
    const Material& m = material_of(s, t);
    EXPECT_EQ(m.albedo, (Vec3f{1, 1, 1})) << t;
    EXPECT_EQ(m.metallic, 1.0f) << t;
    EXPECT_EQ(m.roughness, 1.0f) << t;
  }
  ASSERT_EQ(s.gltf_files.size(), 1u);
  EXPECT_EQ(s.gltf_files[0].nodes, 2u);
  EXPECT_EQ(s.gltf_files[0].mesh_instances, 1u);
  EXPECT_EQ(s.gltf_files[0].triangles, 12u);
}

// The same 26 triangles and materials from an OBJ + MTL and from the glTF
// three ways (external buffer, GLB, data URI): bit for bit, in order.
TEST(GltfLoader, TwinReadsAlike) {
  Warnings w;
  const Scene reference = load("twin.obj", w);
  ASSERT_EQ(reference.triangles.size(), 26u);
  for (const char* name : {"twin.gltf", "twin.glb", "twin_embedded.gltf"}) {
    SCOPED_TRACE(name);
    Warnings gw;
    const Scene s = load(name, gw);
    ASSERT_EQ(s.triangles.size(), reference.triangles.size());
    ASSERT_EQ(s.material_of.size(), s.triangles.size());
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      const Triangle& a = reference.triangles[t];
      const Triangle& b = s.triangles[t];
      EXPECT_TRUE(a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2)
          << "triangle " << t << ": OBJ " << str(a.v0) << str(a.v1) << str(a.v2) << ", glTF " << str(b.v0)
          << str(b.v1) << str(b.v2);
      EXPECT_EQ(material_difference(material_of(reference, t), material_of(s, t)), "")
          << "triangle " << t << ": OBJ material '" << material_of(reference, t).name << "', glTF '"
          << material_of(s, t).name << "'";
    }
    // Neither file gives normals or texture coordinates.
    EXPECT_TRUE(s.normals.empty());
    EXPECT_TRUE(s.uvs.empty());
  }
}

// Strips and fans in the specification's vertex order, UNSIGNED_BYTE indices,
// points and lines skipped with one warning each, a mesh shared by two nodes.
TEST(GltfLoader, Primitives) {
  Warnings w;
  const Scene s = load("primitives.gltf", w);
  using V = Vec3f;
  const V strip[5] = {{0, 1, 0}, {0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {2, 1, 0}};
  const V fan[5] = {{-3, 0, 0}, {-2, 0, 0}, {-2, 1, 0}, {-3, 1, 0}, {-4, 1, 0}};
  const Triangle expected[] = {
      {strip[0], strip[1], strip[2]},
      {strip[1], strip[3], strip[2]},
      {strip[2], strip[3], strip[4]},
      {fan[1], fan[2], fan[0]},
      {fan[2], fan[3], fan[0]},
      {fan[3], fan[4], fan[0]},
      {V{0, 2, 0}, V{1, 2, 0}, V{1, 3, 0}},
      {V{0, 2, 0}, V{1, 3, 0}, V{0, 3, 0}},
      {V{0, -2, 0}, V{1, -2, 0}, V{0, -1, 0}},  // shared_a
      {V{3, -2, 0}, V{4, -2, 0}, V{3, -1, 0}},  // shared_b, translated by 3 in x
  };
  ASSERT_EQ(s.triangles.size(), std::size(expected));
  for (std::size_t t = 0; t < std::size(expected); ++t) {
    const Triangle& a = s.triangles[t];
    const Triangle& b = expected[t];
    EXPECT_TRUE(a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2)
        << "triangle " << t << ": " << str(a.v0) << str(a.v1) << str(a.v2) << ", expected " << str(b.v0) << str(b.v1)
        << str(b.v2);
  }
  EXPECT_EQ(warnings_with(w, "points are not rendered"), 1u) << all(w);
  EXPECT_EQ(warnings_with(w, "lines are not rendered"), 1u) << all(w);
  ASSERT_EQ(s.gltf_files.size(), 1u);
  const GltfSummary& g = s.gltf_files[0];
  EXPECT_EQ(g.nodes, 5u);
  EXPECT_EQ(g.meshes, 4u);
  EXPECT_EQ(g.mesh_instances, 5u);  // mesh 3 counted for both of its nodes
  EXPECT_EQ(g.primitives, 7u);      // 1 + 1 + 3 + 1 + 1, points and lines included
  EXPECT_EQ(g.triangles, 10u);
  // One material, "matte", on every triangle.
  for (std::size_t t = 0; t < s.triangles.size(); ++t) EXPECT_EQ(material_of(s, t).name, "matte") << t;
}

// Perspective cameras only, in the file's order; the first sets the bare
// file's camera and its aspect the film; the orthographic one is warned.
TEST(GltfLoader, Cameras) {
  Warnings w;
  const Scene s = load("cameras.gltf", w);
  ASSERT_EQ(s.cameras.size(), 2u);
  const NamedCamera& wide = s.cameras[0];
  EXPECT_EQ(wide.name, "wide");
  expect_near(wide.spec.eye, {0, 1, 5}, 1e-6, "wide eye");
  // The view direction (look_at lies ahead by max(1, |eye|): far enough for
  // single precision to tell it from the eye).
  expect_near(normalize(wide.spec.look_at - wide.spec.eye), {0, 0, -1}, 1e-6, "wide view");
  expect_near(wide.spec.up, {0, 1, 0}, 1e-6, "wide up");
  EXPECT_FLOAT_EQ(wide.spec.vfov_deg, float(180.0 / kPi));  // 1 radian
  EXPECT_EQ(wide.aspect, 2.0f);
  const NamedCamera& tele = s.cameras[1];
  EXPECT_EQ(tele.name, "tele");
  expect_near(tele.spec.eye, {2, 0, 0}, 1e-6, "tele eye");
  expect_near(normalize(tele.spec.look_at - tele.spec.eye), {-1, 0, 0}, 1e-6, "tele view");  // 90 degrees about +y: -z becomes -x
  expect_near(tele.spec.up, {0, 1, 0}, 1e-6, "tele up");
  EXPECT_FLOAT_EQ(tele.spec.vfov_deg, float(0.25 * 180.0 / kPi));
  EXPECT_EQ(tele.aspect, 0.0f);  // none given
  // The bare file: its first perspective camera, a film of its aspect with the default's longer side.
  EXPECT_EQ(s.camera.eye, wide.spec.eye);
  EXPECT_EQ(s.camera.look_at, wide.spec.look_at);
  EXPECT_EQ(s.camera.vfov_deg, wide.spec.vfov_deg);
  EXPECT_FALSE(s.camera_framed);
  EXPECT_EQ(s.width, 512);
  EXPECT_EQ(s.height, 256);
  const std::string ortho = warning_with(w, "/cameras/0/type");
  EXPECT_NE(ortho, "") << all(w);
  EXPECT_NE(ortho.find("cameras.gltf"), std::string::npos) << ortho;
  EXPECT_NE(ortho.find("orthographic"), std::string::npos) << ortho;
  EXPECT_EQ(s.triangles.size(), 2u);
}

// KHR_lights_punctual: type, world position and direction, candela and lux
// over 683 lm/W, the spot's cone cosines.
TEST(GltfLoader, Lights) {
  {
    Warnings w;
    const Scene s = load("point_light.gltf", w);
    ASSERT_EQ(s.punctual_lights.size(), 1u);
    const PunctualLight& l = s.punctual_lights[0];
    EXPECT_EQ(l.type, PunctualLight::Type::point);
    EXPECT_EQ(l.name, "bulb");
    expect_near(l.position, {0, 2, 0}, 1e-6, "point position");
    EXPECT_EQ(l.intensity, (Vec3f{1, 1, 1}));  // [1, 1, 1] x 683 cd / 683 lm/W
    EXPECT_EQ(l.range, 0.0f);
    ASSERT_EQ(s.gltf_files.size(), 1u);
    EXPECT_EQ(s.gltf_files[0].lights, 1u);
    EXPECT_EQ(s.triangles.size(), 2u);
  }
  {
    Warnings w;
    const Scene s = load("spot_light.gltf", w);
    ASSERT_EQ(s.punctual_lights.size(), 1u);
    const PunctualLight& l = s.punctual_lights[0];
    EXPECT_EQ(l.type, PunctualLight::Type::spot);
    EXPECT_EQ(l.name, "spot");
    expect_near(l.position, {0, 2, 0}, 1e-6, "spot position");
    expect_near(l.direction, {0, -1, 0}, 1e-6, "spot direction");
    EXPECT_NEAR(length(Vec3d(l.direction)), 1.0, 1e-6);
    EXPECT_EQ(l.intensity, (Vec3f{1, 1, 1}));
    EXPECT_FLOAT_EQ(l.cos_inner, float(std::cos(0.25)));
    EXPECT_FLOAT_EQ(l.cos_outer, float(std::cos(0.5)));
    EXPECT_EQ(s.triangles.size(), 2u);
  }
  {
    Warnings w;
    const Scene s = load("directional_light.gltf", w);
    ASSERT_EQ(s.punctual_lights.size(), 1u);
    const PunctualLight& l = s.punctual_lights[0];
    EXPECT_EQ(l.type, PunctualLight::Type::directional);
    EXPECT_EQ(l.name, "sun");
    expect_near(l.direction, {0, -1, 0}, 1e-6, "sun direction");
    EXPECT_NEAR(length(Vec3d(l.direction)), 1.0, 1e-6);
    EXPECT_EQ(l.intensity, (Vec3f{1, 1, 1}));  // 683 lx / 683 lm/W
    EXPECT_EQ(s.triangles.size(), 6u);          // the floor and the blocker's two quads
  }
}

// alphaMode MASK: an opacity map from the base colour texture with the
// factor's alpha and the cutoff; the image from a GLB's buffer view or a file.
TEST(GltfLoader, Masks) {
  {
    Warnings w;
    const Scene s = load("mask.glb", w);
    ASSERT_EQ(s.triangles.size(), 2u);
    const Material& m = material_of(s, 0);
    EXPECT_TRUE(m.cut_out());
    ASSERT_GE(m.maps[std::size_t(MapSlot::opacity)], 0);
    const TextureMap& map = map_of(s, m, MapSlot::opacity);
    EXPECT_EQ(map.slot, MapSlot::opacity);
    EXPECT_EQ(map.alpha_cutoff, 0.5f);
    EXPECT_EQ(map.alpha_factor, 1.0f);
    EXPECT_FALSE(map.warn_without_alpha);
    ASSERT_NE(map.embedded, nullptr);  // the PNG in the BIN chunk
    EXPECT_EQ(std::string(map.embedded->begin(), map.embedded->end()), test::read_file(gltf_dir() / "mask_alpha.png"));
    // The cut-out mask load_scene_images made: the image's left half (alpha 255) opaque, the right half not.
    ASSERT_GE(map.mask, 0);
    ASSERT_LT(std::size_t(map.mask), s.opacity_masks.size());
    const OpacityMask& mask = s.opacity_masks[std::size_t(map.mask)];
    ASSERT_EQ(mask.width, 8);
    ASSERT_EQ(mask.height, 8);
    ASSERT_EQ(mask.opaque.size(), 64u);
    for (int row = 0; row < 8; ++row)
      for (int col = 0; col < 8; ++col)
        EXPECT_EQ(mask.opaque[std::size_t(row * 8 + col)], col < 4 ? 1 : 0) << "row " << row << " column " << col;
  }
  {
    Warnings w;
    const Scene s = load("mask_cutoff.gltf", w);
    const Material& m = material_of(s, 0);
    EXPECT_TRUE(m.cut_out());
    ASSERT_GE(m.maps[std::size_t(MapSlot::opacity)], 0);
    const TextureMap& map = map_of(s, m, MapSlot::opacity);
    EXPECT_EQ(map.alpha_cutoff, 0.75f);
    EXPECT_EQ(map.alpha_factor, 0.5f);
    EXPECT_FALSE(map.warn_without_alpha);
    EXPECT_EQ(map.embedded, nullptr);
    EXPECT_EQ(map.file.filename().string(), "mask_alpha.png");
    EXPECT_TRUE(same_file(map.file, gltf_dir() / "mask_alpha.png")) << map.file;
    // Alpha is at most 1 x 0.5 < 0.75: cut out everywhere.
    ASSERT_GE(map.mask, 0);
    const OpacityMask& mask = s.opacity_masks[std::size_t(map.mask)];
    EXPECT_TRUE(std::all_of(mask.opaque.begin(), mask.opaque.end(), [](std::uint8_t o) { return o == 0; }));
  }
  {
    Warnings w;
    const Scene s = load("blend.gltf", w);
    EXPECT_EQ(warnings_with(w, "BLEND is read as MASK"), 1u) << all(w);
    const Material& m = material_of(s, 0);
    EXPECT_TRUE(m.cut_out());
    ASSERT_GE(m.maps[std::size_t(MapSlot::opacity)], 0);
    EXPECT_EQ(map_of(s, m, MapSlot::opacity).alpha_cutoff, 0.5f);
  }
}

// Base colour and metallic-roughness maps: the channels and linear data
// glTF defines, the sampler's wrap modes; an image in a data URI.
TEST(GltfLoader, Textured) {
  {
    Warnings w;
    const Scene s = load("textured.gltf", w);
    ASSERT_EQ(s.triangles.size(), 2u);
    const Material& m = material_of(s, 0);
    ASSERT_GE(m.maps[std::size_t(MapSlot::base_color)], 0);
    ASSERT_GE(m.maps[std::size_t(MapSlot::roughness)], 0);
    ASSERT_GE(m.maps[std::size_t(MapSlot::metallic)], 0);
    EXPECT_FALSE(m.cut_out());
    const TextureMap& base = map_of(s, m, MapSlot::base_color);
    const TextureMap& rough = map_of(s, m, MapSlot::roughness);
    const TextureMap& metal = map_of(s, m, MapSlot::metallic);
    EXPECT_EQ(base.file.filename().string(), "textured_checker.png");
    EXPECT_EQ(base.embedded, nullptr);
    EXPECT_FALSE(base.linear);
    EXPECT_EQ(base.factor, (Vec3f{1, 1, 1}));
    EXPECT_TRUE(base.srgb);  // an 8-bit colour image, decoded by load_scene_images
    for (const TextureMap* map : {&rough, &metal}) {
      EXPECT_EQ(map->file.filename().string(), "textured_metal_rough.png");
      EXPECT_TRUE(map->linear);
      EXPECT_FALSE(map->srgb);
      EXPECT_EQ(map->factor.x, 1.0f);
    }
    EXPECT_EQ(rough.scalar_channel, 1);  // green
    EXPECT_EQ(metal.scalar_channel, 2);  // blue
    for (const TextureMap* map : {&base, &rough, &metal}) {
      EXPECT_EQ(map->wrap_s, TextureWrap::periodic) << map->keyword;  // REPEAT
      EXPECT_EQ(map->wrap_t, TextureWrap::mirror) << map->keyword;    // MIRRORED_REPEAT
    }
  }
  {
    Warnings w;
    const Scene s = load("textured_data_uri.gltf", w);
    const Material& m = material_of(s, 0);
    ASSERT_GE(m.maps[std::size_t(MapSlot::base_color)], 0);
    const TextureMap& base = map_of(s, m, MapSlot::base_color);
    ASSERT_NE(base.embedded, nullptr);
    EXPECT_EQ(std::string(base.embedded->begin(), base.embedded->end()),
              test::read_file(gltf_dir() / "textured_checker.png"));
    ASSERT_GE(m.maps[std::size_t(MapSlot::roughness)], 0);
    EXPECT_EQ(map_of(s, m, MapSlot::roughness).embedded, nullptr);  // still the file beside it
  }
}

// TEXCOORD_0 of a file's first primitive (here its only one) reaches
// Scene::uvs, stored as an OBJ's v (1 - glTF's v).
TEST(GltfLoader, TextureCoordinatesOfTheFirstPrimitiveAreKept) {
  {
    Warnings w;
    const Scene s = load("textured.gltf", w);
    ASSERT_EQ(s.uvs.size(), s.triangles.size());
    // glTF (0,2) (2,2) (2,0) (0,0) at the quad's corners 0..3; triangles (0,1,2), (0,2,3).
    const Vec2f uv[4] = {{0, -1}, {2, -1}, {2, 1}, {0, 1}};
    const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(s.uvs[std::size_t(t)].uv[k].u, uv[corners[t][k]].u) << "triangle " << t << " corner " << k;
        EXPECT_EQ(s.uvs[std::size_t(t)].uv[k].v, uv[corners[t][k]].v) << "triangle " << t << " corner " << k;
      }
  }
  {
    Warnings w;
    const Scene s = load("mask.glb", w);
    ASSERT_EQ(s.uvs.size(), s.triangles.size());
    // glTF (0,1) (1,1) (1,0) (0,0): the image's top-left corner at the quad's top-left.
    const Vec2f uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const int corners[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; ++t)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(s.uvs[std::size_t(t)].uv[k].u, uv[corners[t][k]].u) << "triangle " << t << " corner " << k;
        EXPECT_EQ(s.uvs[std::size_t(t)].uv[k].v, uv[corners[t][k]].v) << "triangle " << t << " corner " << k;
      }
  }
}

// What Kappa does not model is warned once per kind, naming the element;
// only the default scene is rendered.
TEST(GltfLoader, Extensions) {
  Warnings w;
  const Scene s = load("extensions.gltf", w);
  EXPECT_EQ(s.triangles.size(), 14u);  // scene 0: 7 quads; node 7 is in scene 1
  ASSERT_EQ(s.gltf_files.size(), 1u);
  EXPECT_EQ(s.gltf_files[0].mesh_instances, 7u);
  EXPECT_EQ(s.gltf_files[0].triangles, 14u);
  const std::pair<const char*, const char*> expected[] = {
      {"normal maps", "/materials/0/normalTexture"},
      {"occlusion maps", "/materials/1/occlusionTexture"},
      {"KHR_materials_clearcoat", "/materials/2/extensions/KHR_materials_clearcoat"},
      {"KHR_materials_sheen", "/materials/3/extensions/KHR_materials_sheen"},
      {"KHR_texture_transform", "/materials/4/pbrMetallicRoughness/baseColorTexture"},
      {"KHR_materials_volume", "/materials/5/extensions/KHR_materials_volume"},
      {"texture coordinate set 1", "/materials/6/pbrMetallicRoughness/baseColorTexture/texCoord"},
      {"only scene 0", "/scenes"},
  };
  for (const auto& [text, pointer] : expected) {
    EXPECT_EQ(warnings_with(w, text), 1u) << text << all(w);
    const std::string warning = warning_with(w, text);
    EXPECT_NE(warning.find(pointer), std::string::npos) << warning;
    EXPECT_NE(warning.find("extensions.gltf"), std::string::npos) << warning;
  }
}

// A scene.json's meshes may mix OBJ and glTF files (here by absolute path).
TEST(GltfLoader, SceneJsonMixesObjAndGltf) {
  test::TempDir dir;
  test::write_file(dir / "t.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  const std::filesystem::path twin = gltf_dir() / "twin.gltf";
  test::write_file(dir / "scene.json",
                   "{\"meshes\": [\"t.obj\", " + nlohmann::json(twin.string()).dump() + "]}\n");
  Warnings w;
  const Scene s = load_scene(dir / "scene.json", w);
  Warnings tw;
  const Scene alone = load_scene(twin, tw);
  ASSERT_EQ(alone.triangles.size(), 26u);
  ASSERT_EQ(s.triangles.size(), 1u + alone.triangles.size());
  EXPECT_EQ(s.triangles[0].v0, (Vec3f{-1, -1, 0}));  // the OBJ first, as listed
  for (std::size_t t = 0; t < alone.triangles.size(); ++t) {
    EXPECT_EQ(s.triangles[1 + t].v0, alone.triangles[t].v0) << t;
    EXPECT_EQ(s.triangles[1 + t].v2, alone.triangles[t].v2) << t;
    EXPECT_EQ(material_difference(material_of(s, 1 + t), material_of(alone, t)), "") << t;
  }
  ASSERT_EQ(s.gltf_files.size(), 1u);
  EXPECT_EQ(s.gltf_files[0].triangles, 26u);
  auto has_input = [&](const std::filesystem::path& p) {
    return std::any_of(s.inputs.begin(), s.inputs.end(), [&](const auto& i) { return same_file(i, p); });
  };
  EXPECT_TRUE(has_input(twin));
  EXPECT_TRUE(has_input(gltf_dir() / "twin.bin"));
  EXPECT_TRUE(has_input(dir / "t.obj"));
}

// A mirroring node keeps the front face (glTF: a negative determinant turns
// the winding, so the loader swaps two corners), and normals are carried by
// the inverse transpose (a non-uniform scale bends them).
TEST(GltfLoader, MirroredAndNonUniformlyScaledNodesKeepTheFrontAndBendNormals) {
  test::TempDir dir;
  // One triangle (0,0,0) (1,0,0) (0,1,0), facing +z, its vertex normals (1,1,0)/sqrt2.
  const float r = float(1.0 / std::sqrt(2.0));
  const float data[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, r, r, 0, r, r, 0, r, r, 0};
  test::write_file(dir / "tri.bin", std::string(reinterpret_cast<const char*>(data), sizeof data));
  test::write_file(dir / "m.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0, "scale": [-1, 1, 1]}, {"mesh": 0, "scale": [2, 1, 1], "translation": [0, 0, 5]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "bufferViews": [{"buffer": 0, "byteLength": 72}], "buffers": [{"byteLength": 72, "uri": "tri.bin"}]})");
  Warnings w;
  const Scene s = load_scene(dir / "m.gltf", w);
  ASSERT_EQ(s.triangles.size(), 2u);
  ASSERT_EQ(s.normals.size(), 2u);
  // Mirrored in x: corners 1 and 2 swapped, so the triangle still faces +z.
  const Triangle& m = s.triangles[0];
  EXPECT_EQ(m.v0, (Vec3f{0, 0, 0}));
  EXPECT_EQ(m.v1, (Vec3f{0, 1, 0}));
  EXPECT_EQ(m.v2, (Vec3f{-1, 0, 0}));
  const Vec3f face = cross(m.v1 - m.v0, m.v2 - m.v0);
  EXPECT_GT(face.z, 0.0f);
  // Its normals mirrored too: (-1, 1, 0)/sqrt2.
  for (const Vec3f& n : s.normals[0].n) expect_near(n, {-r, r, 0}, 1e-6, "mirrored normal");
  // Scaled by 2 in x: the normal's x halves before normalising: (0.5, 1, 0)/|.|.
  const float k = float(1.0 / std::sqrt(1.25));
  for (const Vec3f& n : s.normals[1].n) expect_near(n, {0.5f * k, k, 0}, 1e-6, "scaled normal");
  EXPECT_EQ(s.triangles[1].v1, (Vec3f{2, 0, 5}));
}

}  // namespace
}  // namespace kappa
