// Triangles and the watertight ray/triangle test shared by every exact
// accelerator (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1); conservative t bound as in pbrt-v4).
//
// Every exact accelerator must call this one function with the same
// PreparedRay: bitwise-equal inputs give bitwise-equal hits, which is what lets
// the tests demand identical images from naive and grid.
#pragma once

#include <cmath>
#include <limits>
#include <utility>

#include "core/float_util.h"
#include "core/vec3.h"
#include "hit_filter.h"
#include "ray.h"

namespace kappa {

/// A triangle with its vertices stored inline (36 bytes): the accelerators read
/// one contiguous record per test. Counter-clockwise v0, v1, v2 define the
/// geometric normal cross(v1 - v0, v2 - v0).
struct Triangle {
  Vec3f v0, v1, v2;
};

/// Per-ray constants of the watertight test, computed once per query.
struct PreparedRay {
  Vec3f o;
  int kx = 0, ky = 1, kz = 2;  ///< axis permutation: kz is the dominant axis of d
  float Sx = 0, Sy = 0, Sz = 1;  ///< shear taking d to +z

  explicit PreparedRay(const Ray& r) : o(r.o) {
    const Vec3f ad = abs(r.d);
    kz = max_dimension(ad);
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    // Swapping kx and ky keeps the winding, hence the sign of U, V, W, consistent.
    if (r.d[kz] < 0.0f) std::swap(kx, ky);
    Sx = r.d[kx] / r.d[kz];
    Sy = r.d[ky] / r.d[kz];
    Sz = 1.0f / r.d[kz];
  }
};

/// Intersects one triangle. On a hit with tmin < t <= tmax, fills t and the
/// barycentrics and returns true. Edges and vertices shared by two triangles
/// are hit by at least one of them (no ray slips through a closed mesh).
/// Always inlined: it is the innermost call of every walk, and GCC's size
/// limits otherwise leave it a call in some instantiations (the counting
/// walks of a render), which cost them 20 % more instructions per test.
[[gnu::always_inline]] inline bool intersect_triangle(const PreparedRay& r, const Triangle& tri, float tmin, float tmax,
                               float& t_out, float& b0_out, float& b1_out, float& b2_out) {
  // Vertices relative to the origin, permuted so the ray runs along z. Array
  // indexing is cheaper than selecting components by comparisons.
  const float A[3] = {tri.v0.x - r.o.x, tri.v0.y - r.o.y, tri.v0.z - r.o.z};
  const float B[3] = {tri.v1.x - r.o.x, tri.v1.y - r.o.y, tri.v1.z - r.o.z};
  const float C[3] = {tri.v2.x - r.o.x, tri.v2.y - r.o.y, tri.v2.z - r.o.z};

  const float Ax = A[r.kx] - r.Sx * A[r.kz];
  const float Ay = A[r.ky] - r.Sy * A[r.kz];
  const float Bx = B[r.kx] - r.Sx * B[r.kz];
  const float By = B[r.ky] - r.Sy * B[r.kz];
  const float Cx = C[r.kx] - r.Sx * C[r.kz];
  const float Cy = C[r.ky] - r.Sy * C[r.kz];

  // Scaled barycentrics: signed areas of the edges as seen along the ray.
  float U = Cx * By - Cy * Bx;
  float V = Ax * Cy - Ay * Cx;
  float W = Bx * Ay - By * Ax;

  // A zero in float may be a rounding artefact: decide it exactly in double,
  // which is what makes shared edges watertight.
  // Non-short-circuit | and &: the same tests without a branch each.
  if ((U == 0.0f) | (V == 0.0f) | (W == 0.0f)) {
    U = float(double(Cx) * double(By) - double(Cy) * double(Bx));
    V = float(double(Ax) * double(Cy) - double(Ay) * double(Cx));
    W = float(double(Bx) * double(Ay) - double(By) * double(Ax));
  }

  // No back-face culling: the signs must agree, whichever they are.
  if (((U < 0.0f) | (V < 0.0f) | (W < 0.0f)) & ((U > 0.0f) | (V > 0.0f) | (W > 0.0f))) return false;
  const float det = U + V + W;
  if (det == 0.0f) return false;  // degenerate, or the ray lies in the triangle's plane

  const float Az = r.Sz * A[r.kz];
  const float Bz = r.Sz * B[r.kz];
  const float Cz = r.Sz * C[r.kz];
  const float T = U * Az + V * Bz + W * Cz;

  // Range test on the scaled distance before the division (cheap rejection).
  if (det < 0.0f ? (T > tmin * det || T < tmax * det) : (T < tmin * det || T > tmax * det))
    return false;

  const float inv_det = 1.0f / det;
  const float t = T * inv_det;
  if (!(t > tmin && t <= tmax)) return false;

  // Reject hits whose t is not certainly positive given the rounding error of
  // the computation above (pbrt-v4, "Triangle::Intersect", section 6.8.5).
  const float max_zt = max_component(abs(Vec3f{Az, Bz, Cz}));
  const float max_xt = max_component(abs(Vec3f{Ax, Bx, Cx}));
  const float max_yt = max_component(abs(Vec3f{Ay, By, Cy}));
  const float delta_z = gamma(3) * max_zt;
  const float delta_x = gamma(5) * (max_xt + max_zt);
  const float delta_y = gamma(5) * (max_yt + max_zt);
  const float delta_e = 2.0f * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  const float max_e = max_component(abs(Vec3f{U, V, W}));
  const float delta_t =
      3.0f * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * std::abs(inv_det);
  if (t <= delta_t) return false;

  t_out = t;
  b0_out = U * inv_det;
  b1_out = V * inv_det;
  b2_out = W * inv_det;
  return true;
}

/// The tmax a closest-hit walk tests its next triangle with. The range test
/// before the division rounds differently from t itself, so a triangle at
/// exactly best.t could be cut by it, and which of two equal-t triangles
/// survives would depend on test order. A limit a few ulps above best.t lets
/// every equal-t candidate reach the tie rule; closer_than alone decides
/// (best.t starts at ray.tmax, so the ray's range still holds).
[[gnu::always_inline]] inline float closest_limit(const Hit& best) {
  return best.t * (1.0f + 8.0f * std::numeric_limits<float>::epsilon());
}

/// Closest-hit update shared by the exact accelerators: tests one triangle and
/// keeps it if it is closer under closer_than's tie rule and `filter`
/// (hit_filter.h) lets it count.
template <HitFilter Filter = NoHitFilter>
[[gnu::always_inline]] inline void test_closest(const PreparedRay& r, const Triangle& tri, TriangleId id, float tmin,
                                                Hit& best, const Filter& filter = {}) {
  float t, b0, b1, b2;
  if (intersect_triangle(r, tri, tmin, closest_limit(best), t, b0, b1, b2) && closer_than(t, id, best)) {
    const Hit candidate{id, t, b0, b1, b2};
    if (filter_accepts(filter, candidate)) best = candidate;
  }
}

/// Any-hit test shared by the exact accelerators: true if the triangle is hit
/// within [tmin, tmax] and `filter` lets the hit count.
template <HitFilter Filter = NoHitFilter>
[[gnu::always_inline]] inline bool test_any(const PreparedRay& r, const Triangle& tri, TriangleId id, float tmin,
                                            float tmax, const Filter& filter = {}) {
  float t, b0, b1, b2;
  return intersect_triangle(r, tri, tmin, tmax, t, b0, b1, b2) && filter_accepts(filter, Hit{id, t, b0, b1, b2});
}

/// Twice the area of a triangle, computed in double (zero for degenerate ones).
inline double double_area(const Triangle& tri) {
  const Vec3d e1 = Vec3d(tri.v1) - Vec3d(tri.v0);
  const Vec3d e2 = Vec3d(tri.v2) - Vec3d(tri.v0);
  return length(cross(e1, e2));
}

/// Triangles every accelerator may hit: finite vertices and non-zero area.
inline bool usable_triangle(const Triangle& t) {
  return is_finite(t.v0) && is_finite(t.v1) && is_finite(t.v2) && double_area(t) > 0;
}

}  // namespace kappa
