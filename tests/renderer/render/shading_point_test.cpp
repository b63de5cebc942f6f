// A hit becomes a shading point in one place (renderer/render/shading_point.h):
// the geometry is surface_point's, the shading normal and UVs interpolate
// what the mesh gave, and without them the geometric normal and pbrt's UVs.
#include "renderer/render/shading_point.h"

#include <gtest/gtest.h>

namespace kappa {
namespace {

Scene one_triangle() {
  Scene s;
  s.triangles.push_back({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  s.material_of.push_back(0);
  s.materials.push_back(Material{"m", {0.2f, 0.4f, 0.6f}, {0, 0, 0}});
  return s;
}

TEST(ShadingPoint, WithoutVertexAttributesItIsTheGeometry) {
  const Scene s = one_triangle();
  const Hit hit{0, 1.0f, 0.5f, 0.25f, 0.25f};
  const ShadingPoint p = shading_point(s, hit);
  const SurfacePoint g = surface_point(s.triangles[0], 0.5f, 0.25f, 0.25f);
  EXPECT_EQ(p.geometry.p, g.p);
  EXPECT_EQ(p.geometry.n, g.n);
  EXPECT_EQ(p.shading_normal, g.n);
  EXPECT_EQ(p.uv, (Vec2f{0.5f, 0.25f}));  // b1 * (1,0) + b2 * (1,1)
  EXPECT_EQ(p.material, &s.materials[0]);
}

TEST(ShadingPoint, VertexNormalsAndUVsAreInterpolated) {
  Scene s = one_triangle();
  s.normals.push_back(TriangleNormals{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
  TriangleUVs uv;
  uv.uv[0] = {0, 0}, uv.uv[1] = {2, 0}, uv.uv[2] = {0, 4};
  s.uvs.push_back(uv);
  const ShadingPoint p = shading_point(s, Hit{0, 1.0f, 0.5f, 0.5f, 0.0f});
  EXPECT_NEAR(p.shading_normal.x, 0.70710678f, 1e-6f);
  EXPECT_NEAR(p.shading_normal.y, 0.70710678f, 1e-6f);
  EXPECT_EQ(p.shading_normal.z, 0.0f);
  EXPECT_EQ(p.geometry.n, (Vec3f{0, 0, 1}));  // the geometric normal is the triangle's own
  EXPECT_EQ(p.uv, (Vec2f{1, 0}));
}

}  // namespace
}  // namespace kappa
