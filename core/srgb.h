// The sRGB transfer function (IEC 61966-2-1), both ways: what 8- and 16-bit
// textures and environment images are decoded with, and what previews and
// the documentation's pictures are encoded with.
#pragma once

#include <cmath>
#include <cstdint>

namespace kappa {

/// An encoded value in [0, 1] to linear.
inline float srgb_to_linear(float c) {
  return c <= 0.04045f ? c * (1.0f / 12.92f) : std::pow((c + 0.055f) * (1.0f / 1.055f), 2.4f);
}

/// Linear radiance times `scale`, clipped to [0, 1] (NaN to 0), as its 8-bit sRGB code.
inline std::uint8_t linear_to_srgb_byte(float linear, float scale = 1.0f) {
  float c = linear * scale;
  c = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
  const float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return std::uint8_t(std::lround(encoded * 255.0f));
}

}  // namespace kappa
