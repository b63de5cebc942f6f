// Floating-point error bounds (Higham's gamma_n) and one-ulp steps, as used by
// pbrt-v4 for conservative intersection and ray-origin offsets.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

// Every exact accelerator returns bitwise the same hit because each evaluates
// the same float expressions the same way: fast math (reassociation,
// reciprocal tricks, no NaN/inf) would break that silently.
#ifdef __FAST_MATH__
#error "Kappa's exact accelerators need IEEE float semantics: build without -ffast-math / -Ofast"
#endif

namespace kappa {

/// Unit roundoff of float: half the machine epsilon.
inline constexpr float kFloatUnitRoundoff = std::numeric_limits<float>::epsilon() * 0.5f;

/// Bound on the relative error of n successive float operations.
constexpr float gamma(int n) {
  return (float(n) * kFloatUnitRoundoff) / (1.0f - float(n) * kFloatUnitRoundoff);
}

/// The next float towards +infinity (identity on +inf and NaN).
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == -0.0f) v = 0.0f;
  std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  bits = (v >= 0.0f) ? bits + 1 : bits - 1;
  return std::bit_cast<float>(bits);
}

/// The next float towards -infinity.
inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;
  std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
  bits = (v > 0.0f) ? bits - 1 : bits + 1;
  return std::bit_cast<float>(bits);
}

}  // namespace kappa
