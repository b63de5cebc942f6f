// OBJ loading: triangulation, materials, the checks tinyobjloader does not make.
#include "renderer/scene/obj/obj_loader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "test_util.h"

namespace kappa {
namespace {

Scene load(const std::string& obj_text, Warnings& warnings, const std::string& mtl_text = "") {
  test::TempDir dir;
  test::write_file(dir / "m.obj", obj_text);
  if (!mtl_text.empty()) test::write_file(dir / "m.mtl", mtl_text);
  Scene scene;
  load_obj(dir / "m.obj", scene, warnings);
  return scene;
}

std::string error_of(const std::string& obj_text) {
  try {
    Warnings w;
    load(obj_text, w);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ObjLoader, QuadsAreTriangulatedAndMaterialsRead) {
  Warnings w;
  const Scene s = load("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl lamp\nf 1 2 3 4\n", w,
                       "newmtl lamp\nKd 0.25 0.5 0.75\nKe 4 5 6\n");
  EXPECT_TRUE(w.empty());
  ASSERT_EQ(s.triangles.size(), 2u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].albedo, (Vec3f{0.25f, 0.5f, 0.75f}));
  EXPECT_EQ(s.materials[0].emission, (Vec3f{4, 5, 6}));
  EXPECT_EQ(s.material_of[0], 0u);
  // Counter-clockwise winding is kept: the normal is +z.
  const Triangle& t = s.triangles[0];
  EXPECT_GT(cross(t.v1 - t.v0, t.v2 - t.v0).z, 0.0f);
}

// Faces of a smoothing group without normals of their own are smooth-shaded
// (their group's face normals averaged at shared vertices, by area); `s off`
// faces stay flat, and faces with vn keep theirs.
TEST(ObjLoader, SmoothingGroupsWithoutNormalsAreSmoothShaded) {
  Warnings w;
  // Two triangles folded 90 degrees along the edge 1-2, in one group, then
  // the same two with `s off`.
  const std::string fold = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const Scene smooth = load(fold + "s 1\nf 1 2 3\nf 2 1 4\n", w);
  ASSERT_EQ(smooth.normals.size(), 2u);
  ASSERT_TRUE(smooth.normals[0].given());
  // Vertex 1 (index 0 of the first triangle) is shared: the mean of +z and +y.
  const Vec3f shared = smooth.normals[0].n[0];
  EXPECT_NEAR(shared.x, 0.0f, 1e-6f);
  EXPECT_NEAR(shared.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(shared.z, std::sqrt(0.5f), 1e-6f);
  // Vertex 3 belongs to the first triangle alone: its own normal, +z.
  EXPECT_NEAR(smooth.normals[0].n[2].z, 1.0f, 1e-6f);
  const Scene flat = load(fold + "s off\nf 1 2 3\nf 2 1 4\n", w);
  EXPECT_TRUE(flat.normals.empty());
  const Scene given = load(fold + "vn 1 0 0\ns 1\nf 1//1 2//1 3//1\nf 2 1 4\n", w);
  ASSERT_EQ(given.normals.size(), 2u);
  EXPECT_EQ(given.normals[0].n[0], (Vec3f{1, 0, 0}));
  EXPECT_NEAR(given.normals[1].n[2].y, 1.0f, 1e-6f);  // from the faces without vn alone
}

TEST(ObjLoader, RelativeIndicesAndSlashForms) {
  Warnings w;
  const Scene s = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf -3/1/1 -2//1 -1/1\n", w);
  EXPECT_EQ(s.triangles.size(), 1u);
}

TEST(ObjLoader, MissingMaterialsFallBackToGreyWithAWarning) {
  Warnings w;
  const Scene s = load("mtllib nowhere.mtl\nusemtl ghost\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", w);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.materials[s.material_of[0]].albedo, (Vec3f{0.5f, 0.5f, 0.5f}));
  EXPECT_EQ(s.materials[s.material_of[0]].emission, (Vec3f{0, 0, 0}));
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("nowhere.mtl"), std::string::npos);
  EXPECT_NE(w[1].find("ghost"), std::string::npos);
}

TEST(ObjLoader, OutOfRangeColoursAreClampedWithAWarning) {
  Warnings w;
  const Scene s = load("mtllib m.mtl\nusemtl hot\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", w,
                       "newmtl hot\nKd 1.5 -0.2 0.5\nKe -1 2 3\n");
  EXPECT_EQ(s.materials[0].albedo, (Vec3f{1.0f, 0.0f, 0.5f}));
  EXPECT_EQ(s.materials[0].emission, (Vec3f{0, 2, 3}));
  EXPECT_EQ(w.size(), 2u);
}

TEST(ObjLoader, ZeroAreaTrianglesAreDroppedAndCounted) {
  Warnings w;
  const Scene s = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n", w);
  EXPECT_EQ(s.triangles.size(), 1u);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("2 zero-area"), std::string::npos);
}

TEST(ObjLoader, ErrorsNameTheLine) {
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 nan 0\n").find("m.obj:3:"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 0\nv 1 0\n").find("m.obj:2:"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 x\n").find("m.obj:5:"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").find("m.obj:4:"), std::string::npos);
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").find("m.obj:4:"), std::string::npos);
  EXPECT_NE(error_of("v 1e300 0 0\n").find("m.obj:1:"), std::string::npos);
  EXPECT_NE(error_of("v 1 0 0 \x01\n").find("m.obj:1:"), std::string::npos);
  EXPECT_NE(error_of("v 3.1+e2 0 0\n").find("m.obj:1:"), std::string::npos);
}

TEST(ObjLoader, ValidNumberFormatsAreAccepted) {
  Warnings w;
  const Scene s = load("v +1 2. -3.0\nv 1e2 2.E1 -3.1e-2\nv .5 0 0\nf 1 2 3\n", w);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0].v0, (Vec3f{1, 2, -3}));
  EXPECT_EQ(s.triangles[0].v1, (Vec3f{100, 20, -0.031f}));
}

TEST(ObjLoader, ConcavePolygonsWarn) {
  Warnings w;
  // An L-shaped hexagon.
  const Scene s = load("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n", w);
  EXPECT_EQ(s.triangles.size(), 4u);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("m.obj:7: concave"), std::string::npos);
}

TEST(ObjLoader, CrlfAndMissingFinalNewlineLoad) {
  Warnings w;
  EXPECT_EQ(load("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3", w).triangles.size(), 1u);
  EXPECT_TRUE(w.empty());
}

// vn and vt are kept per triangle (the shading point reads them); a face
// without them gets "none"; a file without any keeps no array.
TEST(ObjLoader, VertexNormalsAndTextureCoordinatesAreKeptPerTriangle) {
  Warnings w;
  const Scene plain = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", w);
  EXPECT_TRUE(plain.normals.empty());
  EXPECT_TRUE(plain.uvs.empty());
  const Scene s = load(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
      "vn 0 0 2\nvn 0 1 1\n"
      "vt 0.25 0.5\nvt 1 0\nvt 0 1\n"
      "f 1/1/1 2/2/2 3/3/1\n"
      "f 2 4 3\n",
      w);
  ASSERT_EQ(s.triangles.size(), 2u);
  ASSERT_EQ(s.normals.size(), 2u);
  ASSERT_EQ(s.uvs.size(), 2u);
  EXPECT_TRUE(s.normals[0].given());
  EXPECT_EQ(s.normals[0].n[0], (Vec3f{0, 0, 1}));  // normalised
  EXPECT_NEAR(s.normals[0].n[1].y, 0.70710678f, 1e-6f);
  EXPECT_FALSE(s.normals[1].given());
  EXPECT_EQ(s.uvs[0].uv[0], (Vec2f{0.25f, 0.5f}));
  EXPECT_EQ(s.uvs[0].uv[2], (Vec2f{0, 1}));
  EXPECT_EQ(s.uvs[1].uv[1], (Vec2f{1, 0}));  // pbrt's default (0,0), (1,0), (1,1)
  EXPECT_EQ(s.uvs[1].uv[2], (Vec2f{1, 1}));
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

TEST(ObjLoader, Utf8ByteOrderMarkIsSkipped) {
  Warnings w;
  const Scene s = load("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", w);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0].v0, (Vec3f{0, 0, 0}));
  EXPECT_TRUE(w.empty());
}

// Numbers are never silently changed: an MTL colour that is not a finite
// number in range is refused with file:line (tinyobjloader alone read these
// as 0, switching a light off without a word), and a one-component colour
// is the grey it means.
std::string mtl_error(const std::string& mtl_text) {
  try {
    Warnings w;
    load("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", w, mtl_text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ObjLoader, MtlColoursThatAreNotFiniteNumbersAreRefusedWithTheirLine) {
  const struct {
    const char* mtl;
    const char* says;
  } cases[] = {
      {"newmtl a\nKd 0.5 0.5 0.5\nKe nan 1 1\n", "m.mtl:3: Ke component 'nan' is not finite"},
      {"newmtl a\nKe inf 1 1\n", "m.mtl:2: Ke component 'inf' is not finite"},
      {"newmtl a\nKe abc 1 1\n", "m.mtl:2: Ke component 'abc' is not a number"},
      {"newmtl a\nKd nan\n", "m.mtl:2: Kd component 'nan' is not finite"},
      {"newmtl a\nKe 1e400 1 1\n", "m.mtl:2: Ke component '1e400' is out of the range of a double"},
      {"newmtl a\nKe 1e13 1 1\n", "m.mtl:2: Ke component '1e13' exceeds Kappa's limit of 1e+12"},
      {"newmtl a\nKd 0.5 0.5\n", "m.mtl:2: Kd needs 1 or 3 numbers, found 2"},
  };
  for (const auto& c : cases) {
    const std::string e = mtl_error(c.mtl);
    EXPECT_NE(e.find(c.says), std::string::npos) << c.mtl << " -> '" << e << "'";
  }
}

TEST(ObjLoader, AOneComponentMtlColourIsAGrey) {
  Warnings w;
  const Scene s = load("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", w,
                       "newmtl a\nKd 0.25\nKe 2\n");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].albedo, (Vec3f{0.25f, 0.25f, 0.25f}));
  EXPECT_EQ(s.materials[0].emission, (Vec3f{2, 2, 2}));
  EXPECT_TRUE(w.empty());
}

// Limits said right: a triangle too small for single-precision intersection
// (under 1e-15 across) is left out with a count, not lost without a word; one
// of 1e-14 is kept (and is hit: the camera framing it sees it).
TEST(ObjLoader, TrianglesTooSmallToHitAreDroppedWithACount) {
  Warnings w;
  const Scene s = load("v 0 0 0\nv 1e-16 0 0\nv 0 1e-16 0\nv 0 0 1\nv 1e-14 0 1\nv 0 1e-14 1\nf 1 2 3\nf 4 5 6\n", w);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.triangles[0].v0.z, 1.0f);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("1 triangles smaller than 1e-15 across dropped"), std::string::npos) << w[0];
}

}  // namespace
}  // namespace kappa

namespace kappa {
namespace {

/// The material of the scene's only triangle.
const Material& material_of_first_triangle(const Scene& scene) { return scene.materials.at(scene.material_of.at(0)); }

TEST(ObjLexing, BlanksAreSpacesTabsVerticalTabsAndFormFeedsForEveryReader) {
  Warnings w;
  // The MTL's colour split by a vertical tab and a form feed, the OBJ's
  // statements too: tinyobjloader must read what the scan read.
  const Scene scene = load("mtllib m.mtl\n\vv 0 0 0\nv\f1 0 0\nv 0 1 0\nusemtl g\nf 1\v2 3\n", w,
                           "newmtl g\nKd\v0.2\f0.4 0.6\n");
  EXPECT_TRUE(w.empty()) << w.front();
  ASSERT_EQ(scene.triangles.size(), 1u);
  const Material& m = material_of_first_triangle(scene);
  EXPECT_EQ(m.name, "g");
  EXPECT_FLOAT_EQ(m.albedo.x, 0.2f);
  EXPECT_FLOAT_EQ(m.albedo.y, 0.4f);
  EXPECT_FLOAT_EQ(m.albedo.z, 0.6f);
}

TEST(ObjLexing, CommentsAfterStatementsAndAByteOrderMarkAreNotPartOfThem) {
  Warnings w;
  const Scene scene = load("mtllib m.mtl # the library\nv 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nusemtl red # the wall\nf 1 2 3\n",
                           w, "\xEF\xBB\xBFnewmtl red # a comment\nKd 1 0 0 # pure\n");
  EXPECT_TRUE(w.empty()) << w.front();
  const Material& m = material_of_first_triangle(scene);
  EXPECT_EQ(m.name, "red");
  EXPECT_FLOAT_EQ(m.albedo.x, 1.0f);
  EXPECT_FLOAT_EQ(m.albedo.y, 0.0f);
}

TEST(ObjLexing, EveryLibraryOfAnMtllibIsReadAndADefinitionAgainIsWarnedWithBothPlaces) {
  test::TempDir dir;
  test::write_file(dir / "a.mtl", "newmtl red\nKd 1 0 0\n");
  test::write_file(dir / "b.mtl", "newmtl green\nKd 0 1 0\n\nnewmtl red\nKd 0 0 1\n");
  test::write_file(dir / "m.obj", "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl green\nf 1 2 3\nusemtl red\nf 1 3 2\n");
  Scene scene;
  Warnings w;
  load_obj(dir / "m.obj", scene, w);
  ASSERT_EQ(scene.triangles.size(), 2u);
  EXPECT_EQ(scene.materials.at(scene.material_of[0]).name, "green");
  EXPECT_FLOAT_EQ(scene.materials.at(scene.material_of[0]).albedo.y, 1.0f);
  // The first definition holds, as in Blender 3.4's importer.
  EXPECT_FLOAT_EQ(scene.materials.at(scene.material_of[1]).albedo.x, 1.0f);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("b.mtl:4: material 'red' is defined again; its first definition, at "), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("a.mtl:1, is used"), std::string::npos) << w[0];
}

TEST(ObjLexing, AFaceIndexOfMinusTwoToThe63IsRefusedWithoutOverflow) {
  EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n")
                .find("m.obj:4: relative face index -9223372036854775808 points before the first vertex"),
            std::string::npos);
}

}  // namespace
}  // namespace kappa
