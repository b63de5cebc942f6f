// Random numbers and the sample warps used by the path tracer (the warps
// the BSDFs share with it are in core/warps.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/hash.h"
#include "core/vec3.h"
#include "core/warps.h"

namespace kappa {

/// PCG32 (O'Neill 2014): small state, good statistics, cheap to seed per sample.
class Rng {
 public:
  /// The stream of one camera sample depends only on (seed, pixel, sample
  /// index), never on which thread renders it or in what order.
  Rng(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample) {
    const std::uint64_t key = mix64(mix64(seed ^ 0x9E3779B97F4A7C15ull) ^ pixel);
    m_inc = (mix64(key ^ (sample * 0xD1B54A32D192ED03ull)) << 1u) | 1u;
    m_state = 0;
    next_u32();
    m_state += mix64(key + sample);
    next_u32();
  }

  std::uint32_t next_u32() {
    const std::uint64_t old = m_state;
    m_state = old * 6364136223846793005ull + m_inc;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  /// Uniform in [0, 1), 24 random bits: never returns 1.
  float uniform() { return float(next_u32() >> 8) * 0x1p-24f; }

  /// Uniform in [0, 1) with 53 random bits: for choosing among millions of
  /// lights, where 24 bits would round their probabilities.
  double uniform_double() {
    const std::uint64_t hi = next_u32(), lo = next_u32();
    return double(((hi << 32) | lo) >> 11) * 0x1p-53;
  }

 private:
  std::uint64_t m_state = 0;
  std::uint64_t m_inc = 1;
};

/// Uniform barycentrics on a triangle (Heitz 2019, low-distortion square to triangle map).
inline void sample_triangle(float u1, float u2, float& b0, float& b1, float& b2) {
  if (u2 > u1) {
    b0 = u1 * 0.5f;
    b1 = u2 - b0;
  } else {
    b1 = u2 * 0.5f;
    b0 = u1 - b1;
  }
  b2 = 1.0f - b0 - b1;
}

/// Power heuristic with beta = 2 (Veach 1997).
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  if (std::isinf(a)) return 1.0f;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}


}  // namespace kappa
