// The watertight ray/triangle test of triangle.h on eight triangles at once
// (AVX2), on triangles stored lane by lane (Embree's triangle8v idea): the
// nine vertex coordinates of eight triangles as nine rows of eight floats, so
// that a wide leaf's triangles load without a transpose. Like triangle4.h,
// every lane does the scalar test's float operations in its order, with no
// FMA (AVX2 alone does not enable it, and the build refuses contraction) and
// no reciprocal approximation: a lane's t, barycentrics and verdict are
// bitwise the scalar test's. What reads the ray's tmax is left to accept8(),
// and a lane with a zero edge function is flagged for the scalar test.
//
// The build targets x86-64-v2 (SSE4.2): intersect8 is compiled for AVX2 in
// its own file and called only where avx2_available() says the CPU has it,
// a choice made once (per build of a structure, or per frame), not per ray.
#pragma once

#include <cstdint>

#include "triangle.h"

namespace kappa {

/// Eight triangles, lane-ordered: c[k][i] is coordinate k (v0.x, v0.y, v0.z,
/// v1.x, ..., v2.z) of lane i. Lanes beyond a group's count repeat lane 0.
struct alignas(32) Triangle8 {
  float c[9][8];
};
static_assert(sizeof(Triangle8) == 288);

/// Lanes [0, count) from tri[0 .. count), the rest copies of lane 0.
void pack8(const Triangle* const tri[], int count, Triangle8& out);

/// Eight lanes' tmax-free results (as Lanes4's).
struct Lanes8 {
  alignas(32) float T[8];
  alignas(32) float det[8];
  alignas(32) float t[8];
  alignas(32) float b[3][8];
  int valid = 0;  ///< bit i: lane i passed every test that does not read tmax
  int exact = 0;  ///< bit i: lane i needs the scalar test (a zero edge function)
};

/// Whether this CPU runs intersect8 (AVX2), asked of the CPU once.
bool avx2_available();

/// Tests lanes [0, count) of `tri` (count 1 .. 8) against the prepared ray
/// from tmin on. Only where avx2_available().
void intersect8(const PreparedRay& r, const Triangle8& tri, int count, float tmin, Lanes8& out);

/// The tests of lane i that read tmax, as the scalar test does them: with
/// intersect8's, the scalar intersect_triangle's verdict.
[[gnu::always_inline]] inline bool accept8(const Lanes8& lanes, int i, float tmin, float tmax) {
  const float T = lanes.T[i], det = lanes.det[i];
  if (det < 0.0f ? (T > tmin * det || T < tmax * det) : (T < tmin * det || T > tmax * det)) return false;
  return lanes.t[i] <= tmax;
}

}  // namespace kappa
