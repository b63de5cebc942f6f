// intersect8 compiled for AVX2 alone (the rest of the build is x86-64-v2):
// the same operations as intersect4 (triangle4.h) on eight lanes.
#include "triangle8.h"

#include <immintrin.h>

namespace kappa {

void pack8(const Triangle* const tri[], int count, Triangle8& out) {
  for (int i = 0; i < 8; ++i) {
    const Triangle& t = *tri[i < count ? i : 0];
    const float v[9] = {t.v0.x, t.v0.y, t.v0.z, t.v1.x, t.v1.y, t.v1.z, t.v2.x, t.v2.y, t.v2.z};
    for (int k = 0; k < 9; ++k) out.c[k][i] = v[k];
  }
}

bool avx2_available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

namespace {

// std::max(a, b) = (a < b) ? b : a, NaNs included: maxps returns its second
// operand unless the first is greater.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256 std_max8(__m256 a, __m256 b) { return _mm256_max_ps(b, a); }
[[gnu::target("avx2"), gnu::always_inline]] inline __m256 max_component8(__m256 x, __m256 y, __m256 z) {
  return std_max8(x, std_max8(y, z));
}
[[gnu::target("avx2"), gnu::always_inline]] inline __m256 abs8(__m256 v) {
  return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v);
}

}  // namespace

[[gnu::target("avx2")]] void intersect8(const PreparedRay& r, const Triangle8& tri, int count, float tmin,
                                        Lanes8& out) {
  __m256 v[9];
  for (int k = 0; k < 9; ++k) v[k] = _mm256_load_ps(tri.c[k]);
  // Vertex components relative to the origin.
  const __m256 o[3] = {_mm256_set1_ps(r.o.x), _mm256_set1_ps(r.o.y), _mm256_set1_ps(r.o.z)};
  const __m256 A[3] = {_mm256_sub_ps(v[0], o[0]), _mm256_sub_ps(v[1], o[1]), _mm256_sub_ps(v[2], o[2])};
  const __m256 B[3] = {_mm256_sub_ps(v[3], o[0]), _mm256_sub_ps(v[4], o[1]), _mm256_sub_ps(v[5], o[2])};
  const __m256 C[3] = {_mm256_sub_ps(v[6], o[0]), _mm256_sub_ps(v[7], o[1]), _mm256_sub_ps(v[8], o[2])};
  const __m256 Akx = A[r.kx], Aky = A[r.ky], Akz = A[r.kz];
  const __m256 Bkx = B[r.kx], Bky = B[r.ky], Bkz = B[r.kz];
  const __m256 Ckx = C[r.kx], Cky = C[r.ky], Ckz = C[r.kz];
  const __m256 Sx = _mm256_set1_ps(r.Sx), Sy = _mm256_set1_ps(r.Sy), Sz = _mm256_set1_ps(r.Sz);

  const __m256 Ax = _mm256_sub_ps(Akx, _mm256_mul_ps(Sx, Akz));
  const __m256 Ay = _mm256_sub_ps(Aky, _mm256_mul_ps(Sy, Akz));
  const __m256 Bx = _mm256_sub_ps(Bkx, _mm256_mul_ps(Sx, Bkz));
  const __m256 By = _mm256_sub_ps(Bky, _mm256_mul_ps(Sy, Bkz));
  const __m256 Cx = _mm256_sub_ps(Ckx, _mm256_mul_ps(Sx, Ckz));
  const __m256 Cy = _mm256_sub_ps(Cky, _mm256_mul_ps(Sy, Ckz));

  const __m256 U = _mm256_sub_ps(_mm256_mul_ps(Cx, By), _mm256_mul_ps(Cy, Bx));
  const __m256 V = _mm256_sub_ps(_mm256_mul_ps(Ax, Cy), _mm256_mul_ps(Ay, Cx));
  const __m256 W = _mm256_sub_ps(_mm256_mul_ps(Bx, Ay), _mm256_mul_ps(By, Ax));

  const __m256 zero = _mm256_setzero_ps();
  const int lanes = (1 << count) - 1;
  const __m256 any_zero = _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_EQ_OQ), _mm256_cmp_ps(V, zero, _CMP_EQ_OQ)),
                                       _mm256_cmp_ps(W, zero, _CMP_EQ_OQ));
  out.exact = _mm256_movemask_ps(any_zero) & lanes;

  const __m256 any_negative = _mm256_or_ps(
      _mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_LT_OQ), _mm256_cmp_ps(V, zero, _CMP_LT_OQ)), _mm256_cmp_ps(W, zero, _CMP_LT_OQ));
  const __m256 any_positive = _mm256_or_ps(
      _mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_GT_OQ), _mm256_cmp_ps(V, zero, _CMP_GT_OQ)), _mm256_cmp_ps(W, zero, _CMP_GT_OQ));
  const __m256 det = _mm256_add_ps(_mm256_add_ps(U, V), W);
  __m256 reject = _mm256_or_ps(_mm256_and_ps(any_negative, any_positive), _mm256_cmp_ps(det, zero, _CMP_EQ_OQ));

  const __m256 Az = _mm256_mul_ps(Sz, Akz);
  const __m256 Bz = _mm256_mul_ps(Sz, Bkz);
  const __m256 Cz = _mm256_mul_ps(Sz, Ckz);
  const __m256 T = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(U, Az), _mm256_mul_ps(V, Bz)), _mm256_mul_ps(W, Cz));

  const __m256 inv_det = _mm256_div_ps(_mm256_set1_ps(1.0f), det);
  const __m256 t = _mm256_mul_ps(T, inv_det);
  // !(t > tmin): the half of the scalar test's range check on t that does not read tmax.
  reject = _mm256_or_ps(reject, _mm256_cmp_ps(t, _mm256_set1_ps(tmin), _CMP_NGT_UQ));

  const __m256 max_zt = max_component8(abs8(Az), abs8(Bz), abs8(Cz));
  const __m256 max_xt = max_component8(abs8(Ax), abs8(Bx), abs8(Cx));
  const __m256 max_yt = max_component8(abs8(Ay), abs8(By), abs8(Cy));
  const __m256 delta_z = _mm256_mul_ps(_mm256_set1_ps(gamma(3)), max_zt);
  const __m256 delta_x = _mm256_mul_ps(_mm256_set1_ps(gamma(5)), _mm256_add_ps(max_xt, max_zt));
  const __m256 delta_y = _mm256_mul_ps(_mm256_set1_ps(gamma(5)), _mm256_add_ps(max_yt, max_zt));
  const __m256 delta_e = _mm256_mul_ps(
      _mm256_set1_ps(2.0f),
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(gamma(2)), max_xt), max_yt),
                                  _mm256_mul_ps(delta_y, max_xt)),
                    _mm256_mul_ps(delta_x, max_yt)));
  const __m256 max_e = max_component8(abs8(U), abs8(V), abs8(W));
  const __m256 delta_t = _mm256_mul_ps(
      _mm256_mul_ps(_mm256_set1_ps(3.0f),
                    _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(gamma(3)), max_e), max_zt),
                                                _mm256_mul_ps(delta_e, max_zt)),
                                  _mm256_mul_ps(delta_z, max_e))),
      abs8(inv_det));
  reject = _mm256_or_ps(reject, _mm256_cmp_ps(t, delta_t, _CMP_LE_OQ));

  out.valid = ~_mm256_movemask_ps(reject) & lanes & ~out.exact;
  _mm256_store_ps(out.T, T);
  _mm256_store_ps(out.det, det);
  _mm256_store_ps(out.t, t);
  _mm256_store_ps(out.b[0], _mm256_mul_ps(U, inv_det));
  _mm256_store_ps(out.b[1], _mm256_mul_ps(V, inv_det));
  _mm256_store_ps(out.b[2], _mm256_mul_ps(W, inv_det));
}

}  // namespace kappa
