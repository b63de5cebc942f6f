// Rays and hits: what every accelerator query takes and returns.
#pragma once

#include <cstdint>
#include <limits>

#include "core/vec3.h"

namespace kappa {

using TriangleId = std::uint32_t;
inline constexpr TriangleId kNoTriangle = std::numeric_limits<TriangleId>::max();

/// A ray segment o + t·d for t in (tmin, tmax]. d need not be normalized; t is in
/// units of |d|.
struct Ray {
  Vec3f o;
  Vec3f d;
  float tmin = 0.0f;
  float tmax = std::numeric_limits<float>::infinity();
};

/// The closest intersection found along a ray.
struct Hit {
  TriangleId triangle = kNoTriangle;
  float t = std::numeric_limits<float>::infinity();  ///< ray parameter of the hit
  float b0 = 0, b1 = 0, b2 = 0;                      ///< barycentrics of v0, v1, v2

  bool valid() const { return triangle != kNoTriangle; }
};

/// The one ordering every exact accelerator uses: nearer first, and on an exact
/// tie in t the lower triangle id, so the answer does not depend on the order in
/// which an accelerator happens to test triangles.
inline bool closer_than(float t, TriangleId id, const Hit& best) {
  return t < best.t || (t == best.t && id < best.triangle);
}

}  // namespace kappa
