// The MTL mapping (renderer/scene/obj/mtl_material.cpp): one test per row of
// docs/scene-format.md's table, as Blender 3.4's importer maps the fields,
// and the warnings for what Kappa does not model.
#include "renderer/scene/obj/mtl_material.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include "core/error.h"
#include "renderer/scene/obj/obj_loader.h"
#include "test_util.h"

namespace kappa {
namespace {

/// The first material of an MTL text, with the warnings it gave.
Material material(const std::string& mtl, Warnings& w) {
  const std::vector<MtlRecord> records = read_mtl_records("m.mtl", mtl, w);
  std::set<std::string> warned;
  EXPECT_FALSE(records.empty());
  std::vector<TextureMap> maps;
  return material_from_mtl(records.at(0), "m.mtl", w, warned, maps);
}

Material material(const std::string& mtl) {
  Warnings w;
  return material(mtl, w);
}

Warnings warnings_of(const std::string& mtl) {
  Warnings w;
  material(mtl, w);
  return w;
}

std::string refusal(const std::string& mtl) {
  try {
    Warnings w;
    material(mtl, w);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool any_contains(const Warnings& w, const std::string& text) {
  for (const std::string& s : w)
    if (s.find(text) != std::string::npos) return true;
  return false;
}

TEST(MtlMaterial, KdIsTheBaseColourClampedAndEightTenthsWithout) {
  EXPECT_EQ(material("newmtl a\nKd 0.25 0.5 0.75\n").albedo, (Vec3f{0.25f, 0.5f, 0.75f}));
  EXPECT_EQ(material("newmtl a\n").albedo, (Vec3f{0.8f, 0.8f, 0.8f}));
  Warnings w;
  EXPECT_EQ(material("newmtl a\nKd 1.5 0.5 0.5\n", w).albedo, (Vec3f{1, 0.5f, 0.5f}));
  EXPECT_TRUE(any_contains(w, "m.mtl:2: material 'a': Kd 1.5 0.5 0.5 is outside its valid range")) << w.at(0);
}

TEST(MtlMaterial, KeIsEmission) {
  EXPECT_EQ(material("newmtl a\nKe 17 12 4\n").emission, (Vec3f{17, 12, 4}));
  EXPECT_EQ(material("newmtl a\n").emission, (Vec3f{0, 0, 0}));
}

TEST(MtlMaterial, SpecularIsTheMeanOfKsOrTheHighlightDefault) {
  EXPECT_FLOAT_EQ(material("newmtl a\nKs 0.2 0.4 0.6\n").specular, 0.4f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 2\n").specular, 1.0f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 1\n").specular, 0.0f);
  EXPECT_FLOAT_EQ(material("newmtl a\n").specular, 0.0f);
  EXPECT_TRUE(any_contains(warnings_of("newmtl a\nKs 0.2 0.4 0.6\n"),
                           "m.mtl:2: Ks 0.2 0.4 0.6: a coloured specular is read as its mean"));
}

TEST(MtlMaterial, NsMapsToRoughnessAsBlenderDoes) {
  EXPECT_FLOAT_EQ(material("newmtl a\nNs 250\n").roughness, 1.0f - std::sqrt(0.25f));
  EXPECT_FLOAT_EQ(material("newmtl a\nNs 1000\n").roughness, 0.0f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 2\n").roughness, 0.0f);
  EXPECT_FLOAT_EQ(material("newmtl a\n").roughness, 1.0f);
  Warnings w;
  EXPECT_FLOAT_EQ(material("newmtl a\nNs 4000\n", w).roughness, 0.0f);
  EXPECT_TRUE(any_contains(w, "m.mtl:2: Ns 4000 is outside [0, 1000], clamped to 1000"));
}

TEST(MtlMaterial, PrWinsOverNs) {
  EXPECT_FLOAT_EQ(material("newmtl a\nNs 1000\nPr 0.3\n").roughness, 0.3f);
  Warnings w;
  EXPECT_FLOAT_EQ(material("newmtl a\nPr 3\n", w).roughness, 1.0f);
  EXPECT_TRUE(any_contains(w, "Pr 3 is outside [0, 1], clamped to 1"));
}

TEST(MtlMaterial, ReflectingIllumsTakeMetallicFromKa) {
  for (int illum : {3, 5, 8}) {
    const std::string i = "illum " + std::to_string(illum) + "\n";
    EXPECT_FLOAT_EQ(material("newmtl a\nKa 0.3 0.6 0.9\n" + i).metallic, 0.6f) << illum;
    EXPECT_FLOAT_EQ(material("newmtl a\n" + i).metallic, 1.0f) << illum;
  }
  EXPECT_FLOAT_EQ(material("newmtl a\nKa 0.3 0.6 0.9\nillum 2\n").metallic, 0.0f);
  // The refracting models are glass, not metal (Blender would say metallic here).
  for (int illum : {4, 6, 7, 9}) {
    Warnings w;
    EXPECT_FLOAT_EQ(material("newmtl a\nKa 1 1 1\nillum " + std::to_string(illum) + "\n", w).metallic, 0.0f);
    EXPECT_FLOAT_EQ(material("newmtl a\nillum " + std::to_string(illum) + "\n").metallic, 0.0f);
    EXPECT_TRUE(any_contains(w, "Ka ignored")) << illum;
  }
}

TEST(MtlMaterial, PmWinsOverKaAndIllum) {
  EXPECT_FLOAT_EQ(material("newmtl a\nKa 1 1 1\nillum 3\nPm 0.25\n").metallic, 0.25f);
  EXPECT_FLOAT_EQ(material("newmtl a\nPm 1\n").metallic, 1.0f);
  Warnings w;
  EXPECT_FLOAT_EQ(material("newmtl a\nPm -2\n", w).metallic, 0.0f);
  EXPECT_TRUE(any_contains(w, "Pm -2 is outside [0, 1], clamped to 0"));
}

TEST(MtlMaterial, NiIsTheIorWithBlendersDefaults) {
  EXPECT_FLOAT_EQ(material("newmtl a\nNi 1.33\n").ior, 1.33f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 4\n").ior, 1.5f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 9\n").ior, 1.5f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 6\n").ior, 1.0f);
  EXPECT_FLOAT_EQ(material("newmtl a\nillum 7\n").ior, 1.0f);
  EXPECT_FLOAT_EQ(material("newmtl a\n").ior, 1.5f);
  Warnings w;
  EXPECT_FLOAT_EQ(material("newmtl a\nNi 0.5\n", w).ior, 1.0f);
  EXPECT_TRUE(any_contains(w, "m.mtl:2: Ni 0.5 is below 1"));
  EXPECT_NE(refusal("newmtl a\nNi 0\n").find("m.mtl:2: Ni 0 is not an index of refraction"), std::string::npos);
  EXPECT_NE(refusal("newmtl a\nNi -1.5\n").find("m.mtl:2:"), std::string::npos);
}

TEST(MtlMaterial, TransparentIllumsAreGlassTintedByTf) {
  for (int illum : {4, 6, 7, 9}) {
    const Material m = material("newmtl a\nTf 0.9 0.8 0.7\nNi 1.5\nillum " + std::to_string(illum) + "\n");
    EXPECT_EQ(m.transmission, 1.0f) << illum;
    EXPECT_EQ(m.transmission_tint, (Vec3f{0.9f, 0.8f, 0.7f})) << illum;
  }
  EXPECT_EQ(material("newmtl a\nillum 4\n").transmission_tint, (Vec3f{1, 1, 1}));
  EXPECT_EQ(material("newmtl a\nKt 0.5 0.5 0.5\nillum 7\n").transmission_tint, (Vec3f{0.5f, 0.5f, 0.5f}));
  for (int illum : {0, 1, 2, 3, 5, 8, 10}) EXPECT_EQ(material("newmtl a\nillum " + std::to_string(illum) + "\n").transmission, 0.0f);
}

TEST(MtlMaterial, TfWithoutRefractionIsWarned) {
  Warnings w;
  EXPECT_EQ(material("newmtl a\nTf 1 1 1\nillum 2\n", w).transmission, 0.0f);
  EXPECT_TRUE(any_contains(w, "m.mtl:2: Tf ignored (only illum 4, 6, 7 and 9 refract)"));
  EXPECT_TRUE(warnings_of("newmtl a\nTf 0 0 0\n").empty());
}

TEST(MtlMaterial, OpacityIsDOrOneMinusTrKeptAndWarned) {
  EXPECT_FLOAT_EQ(material("newmtl a\nd 1\n").opacity, 1.0f);
  Warnings w;
  EXPECT_FLOAT_EQ(material("newmtl a\nd 0.25\n", w).opacity, 0.25f);
  EXPECT_TRUE(any_contains(w, "m.mtl:2: d 0.25: partial opacity is not blended; cut-outs are binary"));
  EXPECT_TRUE(any_contains(w, "the surface is invisible (opacity below 0.5)"));
  EXPECT_TRUE(material("newmtl a\nd 0.25\n").cut_out());
  Warnings half;
  EXPECT_FALSE(material("newmtl a\nd 0.5\n", half).cut_out());
  EXPECT_TRUE(any_contains(half, "the surface is opaque (opacity 0.5 or more)"));
  EXPECT_FLOAT_EQ(material("newmtl a\nTr 0.25\n").opacity, 0.75f);
  Warnings both;
  EXPECT_FLOAT_EQ(material("newmtl a\nd 1\nTr 0.5\n", both).opacity, 1.0f);
  EXPECT_TRUE(any_contains(both, "m.mtl:3: Tr ignored (d is given too)"));
}

TEST(MtlMaterial, IllumZeroAndTenRenderAsDiffuseWithAWarning) {
  for (const char* i : {"0", "10"}) {
    Warnings w;
    const Material m = material(std::string("newmtl a\nKs 0 0 0\nillum ") + i + "\n", w);
    EXPECT_TRUE(m.lambertian()) << i;
    EXPECT_TRUE(any_contains(w, std::string("m.mtl:3: illum ") + i + " (")) << i;
  }
}

TEST(MtlMaterial, IllumOutsideItsRangeIsRefused) {
  for (const char* i : {"11", "-1", "2.5", "nan", "x"})
    EXPECT_NE(refusal(std::string("newmtl a\nillum ") + i + "\n").find("m.mtl:2:"), std::string::npos) << i;
}

TEST(MtlMaterial, AmbientIsIgnoredWithAWarningUnlessMetallic) {
  Warnings w;
  EXPECT_FLOAT_EQ(material("newmtl a\nKa 0.2 0.2 0.2\n", w).metallic, 0.0f);
  EXPECT_TRUE(any_contains(w, "m.mtl:2: Ka ignored"));
  EXPECT_TRUE(warnings_of("newmtl a\nKa 0 0 0\n").empty());
}

TEST(MtlMaterial, EveryKeywordNotModelledIsWarnedOncePerFileWithItsLine) {
  const char* keys[] = {"map_Bump e.png", "map_Ka a.png", "map_Ps p.png", "bump b.png", "norm n.png", "disp d.png",
                        "decal c.png", "Ps 0.5", "Pc 0.5", "Pcr 0.1", "aniso 0.2", "anisor 0.1",
                        "sharpness 60", "Km 1", "frobnicate 3"};
  for (const char* k : keys) {
    const std::string keyword = std::string(k).substr(0, std::string(k).find(' '));
    Warnings w;
    const std::vector<MtlRecord> records =
        read_mtl_records("m.mtl", std::string("newmtl a\n") + k + "\nnewmtl b\n" + k + "\n", w);
    std::set<std::string> warned;
    std::vector<TextureMap> maps;
    for (const MtlRecord& r : records) material_from_mtl(r, "m.mtl", w, warned, maps);
    ASSERT_EQ(w.size(), 1u) << k;  // once per file, though two materials have it
    EXPECT_EQ(w[0].rfind("m.mtl:2: " + keyword + " ignored (", 0), 0u) << w[0];
  }
}

TEST(MtlMaterial, ASecondDefinitionIsWarnedAndTheFirstKept) {
  Warnings w;
  const std::vector<MtlRecord> r = read_mtl_records("m.mtl", "newmtl a\nKd 1 0 0\nnewmtl a\nKd 0 1 0\n", w);
  ASSERT_EQ(r.size(), 1u);
  std::set<std::string> warned;
  std::vector<TextureMap> maps;
  EXPECT_EQ(material_from_mtl(r[0], "m.mtl", w, warned, maps).albedo, (Vec3f{1, 0, 0}));
  EXPECT_TRUE(any_contains(w, "m.mtl:3: material 'a' is defined again"));
}

TEST(MtlMaterial, NumbersThatAreNotNumbersAreRefusedWithTheirLine) {
  for (const char* s : {"Ns nan", "Ns abc", "Ni inf", "d 1e400", "Pr -nan", "Pm", "Ns 1 2"})
    EXPECT_NE(refusal(std::string("newmtl a\n") + s + "\n").find("m.mtl:2:"), std::string::npos) << s;
}

TEST(MtlMaterial, TheObjLoaderReadsMaterialsThroughTheMapping) {
  test::TempDir dir;
  test::write_file(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\n");
  test::write_file(dir / "m.mtl", "newmtl glass\nKs 1 1 1\nNs 1000\nNi 1.5\nillum 7\nmap_Ka x.png\nmap_Kd x.png\n");
  test::write_file(dir / "x.png", "not read by load_obj");
  Scene scene;
  Warnings w;
  load_obj(dir / "m.obj", scene, w);
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.transmission, 1.0f);
  EXPECT_EQ(m.roughness, 0.0f);
  EXPECT_EQ(m.metallic, 0.0f);  // glass, not Blender's metal of illum 7 without Ka
  EXPECT_FALSE(m.lambertian());
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("m.mtl:6: map_Ka ignored"), std::string::npos) << w[0];
  // The map is the scene's, and its file an input no output may replace.
  ASSERT_EQ(scene.texture_maps.size(), 1u);
  EXPECT_EQ(scene.texture_maps[0].file, dir / "x.png");
  EXPECT_EQ(m.maps[std::size_t(MapSlot::base_color)], 0);
  EXPECT_EQ(std::count(scene.inputs.begin(), scene.inputs.end(), dir / "x.png"), 1);
}

}  // namespace
}  // namespace kappa
