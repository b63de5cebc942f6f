// A surface point reconstructed from a hit, with the rounding-error bound that
// lets secondary rays leave it without self-intersection (pbrt-v4's
// OffsetRayOrigin): no scene-dependent epsilon.
#pragma once

#include "accel/ray.h"
#include "accel/triangle.h"
#include "core/float_util.h"

namespace kappa {

struct SurfacePoint {
  Vec3f p;      ///< position, interpolated from the barycentrics
  Vec3f error;  ///< conservative bound on |p - exact point| per axis
  Vec3f n;      ///< unit geometric normal, cross(v1 - v0, v2 - v0)
};

inline SurfacePoint surface_point(const Triangle& tri, float b0, float b1, float b2) {
  SurfacePoint s;
  s.p = tri.v0 * b0 + tri.v1 * b1 + tri.v2 * b2;
  s.error = (abs(tri.v0 * b0) + abs(tri.v1 * b1) + abs(tri.v2 * b2)) * gamma(7);
  // In double: the float cross product of a tiny but valid triangle can be 0.
  const Vec3d n = cross(Vec3d(tri.v1) - Vec3d(tri.v0), Vec3d(tri.v2) - Vec3d(tri.v0));
  s.n = Vec3f(normalize(n));
  return s;
}

/// The point just off the surface on the side of w, beyond the error bound,
/// rounded away from the surface.
inline Vec3f offset_ray_origin(const SurfacePoint& s, const Vec3f& w) {
  const float d = dot(abs(s.n), s.error);
  Vec3f offset = s.n * d;
  if (dot(w, s.n) < 0.0f) offset = -offset;
  Vec3f po = s.p + offset;
  auto round_away = [](float& c, float o) {
    if (o > 0.0f) c = next_float_up(c);
    else if (o < 0.0f) c = next_float_down(c);
  };
  round_away(po.x, offset.x);
  round_away(po.y, offset.y);
  round_away(po.z, offset.z);
  return po;
}

/// Fraction of a shadow ray's length left unchecked at the far end, so that
/// the target surface itself does not count as an occluder (pbrt-v4's
/// ShadowEpsilon; the far point is offset as well).
inline constexpr float kShadowEpsilon = 1e-4f;

}  // namespace kappa
