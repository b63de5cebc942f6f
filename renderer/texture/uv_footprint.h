// A texture lookup's footprint at the camera ray's hit, from the camera's
// ray differentials (pbrt-v4's approach): the rays through the next pixel
// across and down meet the hit's tangent plane at p + dp/dx and p + dp/dy;
// the triangle's dp/du and dp/dv turn those into (u, v) per pixel (least
// squares, as pbrt-v4's SurfaceInteraction::ComputeDifferentials). Secondary
// rays look textures up with no footprint (the finest level): a path's
// spread after a bounce is not tracked (docs/scene-format.md).
#pragma once

#include <algorithm>
#include <cmath>

#include "accel/triangle.h"
#include "core/vec3.h"
#include "renderer/scene/scene.h"
#include "renderer/texture/texture_lookup.h"

namespace kappa {

/// (u, v) per pixel at a point of `tri` whose position moves by dpdx, dpdy
/// per pixel; zero where the triangle's (u, v) are degenerate.
inline UvFootprint uv_footprint(const Triangle& tri, const TriangleUVs& uvs, const Vec3f& dpdx, const Vec3f& dpdy) {
  const Vec2f duv02 = uvs.uv[0] - uvs.uv[2], duv12 = uvs.uv[1] - uvs.uv[2];
  const Vec3f dp02 = tri.v0 - tri.v2, dp12 = tri.v1 - tri.v2;
  const float det = duv02.u * duv12.v - duv02.v * duv12.u;
  if (!(std::abs(det) > 1e-12f)) return {};
  const float inv = 1.0f / det;
  const Vec3f dpdu = (dp02 * duv12.v - dp12 * duv02.v) * inv;
  const Vec3f dpdv = (dp12 * duv02.u - dp02 * duv12.u) * inv;
  const float a00 = dot(dpdu, dpdu), a01 = dot(dpdu, dpdv), a11 = dot(dpdv, dpdv);
  const float d = a00 * a11 - a01 * a01;
  if (!(d > 0.0f) || !std::isfinite(d)) return {};
  const float inv_d = 1.0f / d;
  auto solve = [&](const Vec3f& dp, float& du, float& dv) {
    const float b0 = dot(dpdu, dp), b1 = dot(dpdv, dp);
    du = std::clamp((a11 * b0 - a01 * b1) * inv_d, -1e8f, 1e8f);
    dv = std::clamp((a00 * b1 - a01 * b0) * inv_d, -1e8f, 1e8f);
    if (!std::isfinite(du)) du = 0.0f;
    if (!std::isfinite(dv)) dv = 0.0f;
  };
  UvFootprint f;
  solve(dpdx, f.dudx, f.dvdx);
  solve(dpdy, f.dudy, f.dvdy);
  return f;
}

}  // namespace kappa
