// The one place a hit becomes a shading point: from the accelerator's answer
// (triangle, t, barycentrics) to what shading reads (position and its error
// bound, geometric normal, shading normal, texture coordinates, material).
// The BSDF layer reads a ShadingPoint and never an accelerator's Hit, so new
// materials add files without touching the accelerators.
#pragma once

#include "accel/ray.h"
#include "core/vec2.h"
#include "renderer/render/interaction.h"
#include "renderer/scene/scene.h"

namespace kappa {

struct ShadingPoint {
  SurfacePoint geometry;  ///< position, its error bound, unit geometric normal
  /// Unit normal interpolated from the mesh's vertex normals (not yet faced
  /// towards the ray), or the geometric normal where the mesh gives none.
  Vec3f shading_normal;
  Vec2f uv;  ///< texture coordinates at the hit (pbrt's defaults without any)
  const Material* material = nullptr;
};

inline ShadingPoint shading_point(const Scene& scene, const Hit& hit) {
  ShadingPoint s;
  s.geometry = surface_point(scene.triangles[hit.triangle], hit.b0, hit.b1, hit.b2);
  s.material = &scene.materials[scene.material_of[hit.triangle]];
  s.shading_normal = s.geometry.n;
  if (hit.triangle < scene.normals.size()) {
    const TriangleNormals& n = scene.normals[hit.triangle];
    if (n.given()) {
      const Vec3f interpolated = n.n[0] * hit.b0 + n.n[1] * hit.b1 + n.n[2] * hit.b2;
      const float len = length(interpolated);
      if (len > 0.0f) s.shading_normal = interpolated / len;
    }
  }
  const TriangleUVs uvs = hit.triangle < scene.uvs.size() ? scene.uvs[hit.triangle] : TriangleUVs{};
  s.uv = uvs.uv[0] * hit.b0 + uvs.uv[1] * hit.b1 + uvs.uv[2] * hit.b2;
  return s;
}

}  // namespace kappa
