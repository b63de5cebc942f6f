// The watertight ray/triangle test of triangle.h on four triangles at once
// (SSE, the build's x86-64-v2), for walks that test a cell's triangles
// together. Every lane does the scalar test's float operations in the same
// order, with no FMA (the build refuses contracting flags) and no
// reciprocal approximation, so a lane's t, barycentrics and verdict are
// bitwise the scalar test's: images stay those of naive and grid.
//
// What depends on the ray's current tmax (the range test before the
// division and t <= tmax) is left to accept4(), which a closest-hit walk
// calls lane by lane in list order with the limit the scalar walk would have
// used for that triangle. A lane where U, V or W is zero in float, which the
// scalar test decides again in double, is flagged for the scalar test.
#pragma once

#include <immintrin.h>

#include "triangle.h"

namespace kappa {

static_assert(sizeof(Triangle) == 36, "intersect4 loads a triangle's nine floats from its record");

/// Four lanes' tmax-free results.
struct Lanes4 {
  alignas(16) float T[4];
  alignas(16) float det[4];
  alignas(16) float t[4];
  alignas(16) float b[3][4];
  int valid = 0;  ///< bit i: lane i passed every test that does not read tmax
  int exact = 0;  ///< bit i: lane i needs the scalar test (a zero edge function)
};

namespace detail {

/// std::max(a, b) = (a < b) ? b : a, NaNs included: maxps returns its
/// second operand unless the first is greater.
[[gnu::always_inline]] inline __m128 std_max4(__m128 a, __m128 b) { return _mm_max_ps(b, a); }
/// max_component(v) = std::max(x, std::max(y, z)).
[[gnu::always_inline]] inline __m128 max_component4(__m128 x, __m128 y, __m128 z) {
  return std_max4(x, std_max4(y, z));
}
[[gnu::always_inline]] inline __m128 abs4(__m128 v) { return _mm_andnot_ps(_mm_set1_ps(-0.0f), v); }

}  // namespace detail

/// Tests tri[0 .. count) (count 1 .. 4; lanes beyond it repeat lane 0 and
/// are masked out) against the prepared ray from tmin on.
[[gnu::always_inline]] inline void intersect4(const PreparedRay& r, const Triangle* const tri[4], int count, float tmin,
                                              Lanes4& out) {
  using namespace detail;
  // Each lane's nine coordinates by three unaligned loads within its
  // 36-byte record (at bytes 0, 12 and 20, so that none reads past it),
  // transposed into one vector per vertex component.
  __m128 v0[4], v1[4], v2[4];
  for (int i = 0; i < 4; ++i) {
    const float* p = &(i < count ? tri[i] : tri[0])->v0.x;
    v0[i] = _mm_loadu_ps(p);      // v0.x v0.y v0.z v1.x
    v1[i] = _mm_loadu_ps(p + 3);  // v1.x v1.y v1.z v2.x
    v2[i] = _mm_loadu_ps(p + 5);  // v1.z v2.x v2.y v2.z
  }
  _MM_TRANSPOSE4_PS(v0[0], v0[1], v0[2], v0[3]);
  _MM_TRANSPOSE4_PS(v1[0], v1[1], v1[2], v1[3]);
  _MM_TRANSPOSE4_PS(v2[0], v2[1], v2[2], v2[3]);
  // Vertex components relative to the origin: A[k] = v0[k] - o[k], C's from v2[k + 1].
  const __m128 o[3] = {_mm_set1_ps(r.o.x), _mm_set1_ps(r.o.y), _mm_set1_ps(r.o.z)};
  const __m128 A[3] = {_mm_sub_ps(v0[0], o[0]), _mm_sub_ps(v0[1], o[1]), _mm_sub_ps(v0[2], o[2])};
  const __m128 B[3] = {_mm_sub_ps(v1[0], o[0]), _mm_sub_ps(v1[1], o[1]), _mm_sub_ps(v1[2], o[2])};
  const __m128 C[3] = {_mm_sub_ps(v2[1], o[0]), _mm_sub_ps(v2[2], o[1]), _mm_sub_ps(v2[3], o[2])};
  const __m128 Akx = A[r.kx], Aky = A[r.ky], Akz = A[r.kz];
  const __m128 Bkx = B[r.kx], Bky = B[r.ky], Bkz = B[r.kz];
  const __m128 Ckx = C[r.kx], Cky = C[r.ky], Ckz = C[r.kz];
  const __m128 Sx = _mm_set1_ps(r.Sx), Sy = _mm_set1_ps(r.Sy), Sz = _mm_set1_ps(r.Sz);

  const __m128 Ax = _mm_sub_ps(Akx, _mm_mul_ps(Sx, Akz));
  const __m128 Ay = _mm_sub_ps(Aky, _mm_mul_ps(Sy, Akz));
  const __m128 Bx = _mm_sub_ps(Bkx, _mm_mul_ps(Sx, Bkz));
  const __m128 By = _mm_sub_ps(Bky, _mm_mul_ps(Sy, Bkz));
  const __m128 Cx = _mm_sub_ps(Ckx, _mm_mul_ps(Sx, Ckz));
  const __m128 Cy = _mm_sub_ps(Cky, _mm_mul_ps(Sy, Ckz));

  const __m128 U = _mm_sub_ps(_mm_mul_ps(Cx, By), _mm_mul_ps(Cy, Bx));
  const __m128 V = _mm_sub_ps(_mm_mul_ps(Ax, Cy), _mm_mul_ps(Ay, Cx));
  const __m128 W = _mm_sub_ps(_mm_mul_ps(Bx, Ay), _mm_mul_ps(By, Ax));

  const __m128 zero = _mm_setzero_ps();
  const int lanes = (1 << count) - 1;
  const __m128 any_zero = _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(U, zero), _mm_cmpeq_ps(V, zero)), _mm_cmpeq_ps(W, zero));
  out.exact = _mm_movemask_ps(any_zero) & lanes;

  const __m128 any_negative = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(U, zero), _mm_cmplt_ps(V, zero)), _mm_cmplt_ps(W, zero));
  const __m128 any_positive = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(U, zero), _mm_cmpgt_ps(V, zero)), _mm_cmpgt_ps(W, zero));
  const __m128 det = _mm_add_ps(_mm_add_ps(U, V), W);
  __m128 reject = _mm_or_ps(_mm_and_ps(any_negative, any_positive), _mm_cmpeq_ps(det, zero));

  const __m128 Az = _mm_mul_ps(Sz, Akz);
  const __m128 Bz = _mm_mul_ps(Sz, Bkz);
  const __m128 Cz = _mm_mul_ps(Sz, Ckz);
  const __m128 T = _mm_add_ps(_mm_add_ps(_mm_mul_ps(U, Az), _mm_mul_ps(V, Bz)), _mm_mul_ps(W, Cz));

  const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
  const __m128 t = _mm_mul_ps(T, inv_det);
  // !(t > tmin): the half of the scalar test's range check on t that does not read tmax.
  reject = _mm_or_ps(reject, _mm_cmpngt_ps(t, _mm_set1_ps(tmin)));

  const __m128 max_zt = max_component4(abs4(Az), abs4(Bz), abs4(Cz));
  const __m128 max_xt = max_component4(abs4(Ax), abs4(Bx), abs4(Cx));
  const __m128 max_yt = max_component4(abs4(Ay), abs4(By), abs4(Cy));
  const __m128 delta_z = _mm_mul_ps(_mm_set1_ps(gamma(3)), max_zt);
  const __m128 delta_x = _mm_mul_ps(_mm_set1_ps(gamma(5)), _mm_add_ps(max_xt, max_zt));
  const __m128 delta_y = _mm_mul_ps(_mm_set1_ps(gamma(5)), _mm_add_ps(max_yt, max_zt));
  const __m128 delta_e = _mm_mul_ps(
      _mm_set1_ps(2.0f),
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(gamma(2)), max_xt), max_yt), _mm_mul_ps(delta_y, max_xt)),
                 _mm_mul_ps(delta_x, max_yt)));
  const __m128 max_e = max_component4(abs4(U), abs4(V), abs4(W));
  const __m128 delta_t = _mm_mul_ps(
      _mm_mul_ps(_mm_set1_ps(3.0f),
                 _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(gamma(3)), max_e), max_zt),
                                       _mm_mul_ps(delta_e, max_zt)),
                            _mm_mul_ps(delta_z, max_e))),
      abs4(inv_det));
  reject = _mm_or_ps(reject, _mm_cmple_ps(t, delta_t));

  out.valid = ~_mm_movemask_ps(reject) & lanes & ~out.exact;
  _mm_store_ps(out.T, T);
  _mm_store_ps(out.det, det);
  _mm_store_ps(out.t, t);
  _mm_store_ps(out.b[0], _mm_mul_ps(U, inv_det));
  _mm_store_ps(out.b[1], _mm_mul_ps(V, inv_det));
  _mm_store_ps(out.b[2], _mm_mul_ps(W, inv_det));
}

/// The tests of lane i that read tmax, as the scalar test does them (the
/// range test on the scaled distance, then t <= tmax): with the tmax-free
/// ones of intersect4, the scalar intersect_triangle's verdict.
[[gnu::always_inline]] inline bool accept4(const Lanes4& lanes, int i, float tmin, float tmax) {
  const float T = lanes.T[i], det = lanes.det[i];
  if (det < 0.0f ? (T > tmin * det || T < tmax * det) : (T < tmin * det || T > tmax * det)) return false;
  return lanes.t[i] <= tmax;
}

}  // namespace kappa
