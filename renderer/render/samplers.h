// The numbers a path consumes, by dimension: a sampler gives each camera
// sample (pixel, sample index) its values for every dimension of the path,
// deterministically, whatever the thread that renders it. Dimensions are
// assigned along the path (path_dimensions below), so that a stratifying
// sampler stratifies the same decision in every path: the pixel position,
// then per bounce the light choice, the point on the light, the BSDF
// direction and Russian roulette.
//
//   independent  PCG32 numbers drawn in order (the dimension is ignored)
//   stratified   jittered strata of the pixel's spp samples, per dimension,
//                their order shuffled per dimension: needs the total
//   sobol        the Sobol (0,2)-sequence, Owen-scrambled, its sample order
//                shuffled per dimension pair with a nested uniform scramble
//                of the index (Burley 2020, "Practical Hash-based Owen
//                Scrambling"; Cycles' sobol-burley): every pair a path uses
//                is a (0,2)-sequence, the first 2^m samples of a pixel a
//                (0,m,2)-net, without knowing the total
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "core/hash.h"
#include "renderer/render/sampler_kind.h"
#include "renderer/render/sampling.h"

namespace kappa {

/// Where each decision of a path reads its numbers.
namespace path_dimensions {
inline constexpr std::uint32_t kPixel = 0;  ///< 2D: the position in the pixel
inline constexpr std::uint32_t kPerBounce = 6;
inline constexpr std::uint32_t light_choice(int bounce) { return 2 + kPerBounce * std::uint32_t(bounce); }  ///< 1D
inline constexpr std::uint32_t light_point(int bounce) { return light_choice(bounce) + 1; }  ///< 2D
inline constexpr std::uint32_t bsdf(int bounce) { return light_choice(bounce) + 3; }         ///< 2D
inline constexpr std::uint32_t roulette(int bounce) { return light_choice(bounce) + 5; }     ///< 1D
/// 1D: which of a layered BSDF's lobes samples the bounce. Numbered apart
/// from the six above, so that the Lambertian frames read exactly the
/// dimensions they read before materials existed.
inline constexpr std::uint32_t bsdf_lobe(int bounce) { return 0x40000000u + std::uint32_t(bounce); }
}  // namespace path_dimensions

/// Uniform in [0, 1) from 32 bits: 24 of them, so 1 is never returned.
inline float unit_float(std::uint32_t bits) { return float(bits >> 8) * 0x1p-24f; }

class IndependentSampler {
 public:
  IndependentSampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample, std::uint32_t /*spp*/)
      : m_rng(seed, pixel, sample) {}
  float get1D(std::uint32_t /*dimension*/) { return m_rng.uniform(); }
  double get1D_double(std::uint32_t /*dimension*/) { return m_rng.uniform_double(); }
  std::pair<float, float> get2D(std::uint32_t /*dimension*/) {
    const float u = m_rng.uniform();
    return {u, m_rng.uniform()};
  }

 private:
  Rng m_rng;
};

inline std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  return __builtin_bswap32(x);
}

/// Owen scrambling of base-2 digits by hashing (Laine & Karras 2011, as
/// Burley 2020 gives it): bit k of the result flips by a hash of the bits
/// above it, so nets stay nets.
/// Laine and Karras's permutation, on the bits reversed: each bit flips by
/// a hash of the bits below it.
inline std::uint32_t laine_karras_permutation(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
inline std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

/// The first two dimensions of Sobol's sequence, as 32-bit fractions: the
/// van der Corput sequence and its companion (generator matrix: Pascal's
/// triangle mod 2), together a (0,2)-sequence in base 2.
inline std::uint32_t sobol_dimension0(std::uint32_t index) { return reverse_bits(index); }
/// Bit by bit, as the generator matrix reads: column i, for bit i of the
/// index, is v_i with v_0 = 2^31 and v_{i+1} = v_i ^ (v_i >> 1).
constexpr std::uint32_t sobol_dimension1_bitwise(std::uint32_t index) {
  std::uint32_t x = 0;
  for (std::uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) x ^= v;
  return x;
}
/// The same sums, a byte of the index at a time: the index is scrambled to
/// all 32 bits, and 32 dependent steps per number cost more than the path's
/// other arithmetic (the sampler ran 25 % slower than PCG32 on the Cornell box).
inline constexpr auto kSobolDimension1Bytes = [] {
  std::array<std::array<std::uint32_t, 256>, 4> table{};
  for (std::uint32_t b = 0; b < 4; ++b)
    for (std::uint32_t byte = 0; byte < 256; ++byte) table[b][byte] = sobol_dimension1_bitwise(byte << (8 * b));
  return table;
}();
inline std::uint32_t sobol_dimension1(std::uint32_t index) {
  return kSobolDimension1Bytes[0][index & 0xFFu] ^ kSobolDimension1Bytes[1][(index >> 8) & 0xFFu] ^
         kSobolDimension1Bytes[2][(index >> 16) & 0xFFu] ^ kSobolDimension1Bytes[3][index >> 24];
}
/// reverse_bits(sobol_dimension1(index)), from tables of reversed sums (bit
/// reversal commutes with XOR): what the scramble reads.
constexpr std::uint32_t reverse_bits_constexpr(std::uint32_t x) {
  std::uint32_t r = 0;
  for (int i = 0; i < 32; ++i, x >>= 1) r = (r << 1) | (x & 1u);
  return r;
}
inline constexpr auto kSobolDimension1BytesReversed = [] {
  std::array<std::array<std::uint32_t, 256>, 4> table{};
  for (std::uint32_t b = 0; b < 4; ++b)
    for (std::uint32_t byte = 0; byte < 256; ++byte)
      table[b][byte] = reverse_bits_constexpr(sobol_dimension1_bitwise(byte << (8 * b)));
  return table;
}();
inline std::uint32_t sobol_dimension1_reversed(std::uint32_t index) {
  return kSobolDimension1BytesReversed[0][index & 0xFFu] ^ kSobolDimension1BytesReversed[1][(index >> 8) & 0xFFu] ^
         kSobolDimension1BytesReversed[2][(index >> 16) & 0xFFu] ^ kSobolDimension1BytesReversed[3][index >> 24];
}

class SobolSampler {
 public:
  SobolSampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample, std::uint32_t /*spp*/)
      : m_key(mix64(mix64(seed ^ 0x5F3759DF0B5E55EDull) ^ pixel)), m_index(std::uint32_t(sample)),
        m_reversed_index(reverse_bits(m_index)) {}

  float get1D(std::uint32_t dimension) { return unit_float(value(dimension, 0)); }
  double get1D_double(std::uint32_t dimension) {
    // 32 stratified bits, and 21 hashed ones below them.
    const std::uint64_t low = mix64(m_key ^ (std::uint64_t(dimension) << 32) ^ m_index) >> 43;
    return double((std::uint64_t(value(dimension, 0)) << 21) | low) * 0x1p-53;
  }
  std::pair<float, float> get2D(std::uint32_t dimension) {
    // Both components share the dimension's hash and its order of the samples.
    const std::uint64_t h = hash(dimension);
    const std::uint32_t index = shuffled_index(h);
    return {unit_float(component(index, h, 0)), unit_float(component(index, h, 1))};
  }

 private:
  std::uint64_t hash(std::uint32_t dimension) const {
    return mix64(m_key ^ (std::uint64_t(dimension) * 0x9E3779B97F4A7C15ull));
  }
  /// The dimension's own order of the samples: nested_uniform_scramble of
  /// the sample index, its first reversal done once per sample.
  std::uint32_t shuffled_index(std::uint64_t h) const {
    return reverse_bits(laine_karras_permutation(m_reversed_index, std::uint32_t(h)));
  }
  /// Component `axis` (0 or 1) of the dimension's point, with its own
  /// scramble: nested_uniform_scramble(sobol_dimension<axis>(index)), whose
  /// first reversal undoes dimension 0's and is tabulated for dimension 1.
  static std::uint32_t component(std::uint32_t index, std::uint64_t h, int axis) {
    const std::uint32_t reversed = axis == 0 ? index : sobol_dimension1_reversed(index);
    return reverse_bits(laine_karras_permutation(reversed, std::uint32_t(h >> 32) ^ (axis ? 0xA511E9B3u : 0u)));
  }
  std::uint32_t value(std::uint32_t dimension, int axis) const {
    const std::uint64_t h = hash(dimension);
    return component(shuffled_index(h), h, axis);
  }

  std::uint64_t m_key;
  std::uint32_t m_index;
  std::uint32_t m_reversed_index;  ///< the same, bits reversed
};

/// Element i of a pseudo-random permutation of [0, n) (Kensler 2013's
/// cycle-walking hash, as pbrt-v4's PermutationElement).
std::uint32_t permutation_element(std::uint32_t i, std::uint32_t n, std::uint32_t seed);

class StratifiedSampler {
 public:
  /// `spp` strata per dimension: 1D in spp intervals, 2D in an nx x ny grid
  /// with nx the largest divisor of spp not above its square root.
  StratifiedSampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample, std::uint32_t spp)
      : m_key(mix64(mix64(seed ^ 0x2545F4914F6CDD1Dull) ^ pixel)), m_index(std::uint32_t(sample)), m_spp(spp),
        m_nx(columns(spp)) {}

  float get1D(std::uint32_t dimension) {
    const std::uint64_t j = jitter(dimension);
    return within((float(stratum(dimension)) + unit_float(std::uint32_t(j))) / float(m_spp));
  }
  double get1D_double(std::uint32_t dimension) {
    const double u = (double(stratum(dimension)) + double(jitter(dimension) >> 11) * 0x1p-53) / double(m_spp);
    return u < 1.0 ? u : std::nextafter(1.0, 0.0);
  }
  std::pair<float, float> get2D(std::uint32_t dimension) {
    const std::uint64_t j = jitter(dimension);
    const std::uint32_t stratum = this->stratum(dimension);
    const std::uint32_t ny = m_spp / m_nx;
    return {within((float(stratum % m_nx) + unit_float(std::uint32_t(j))) / float(m_nx)),
            within((float(stratum / m_nx) + unit_float(std::uint32_t(j >> 32))) / float(ny))};
  }

 private:
  static std::uint32_t columns(std::uint32_t spp) {
    std::uint32_t nx = std::uint32_t(std::sqrt(double(spp)));
    while (nx > 1 && spp % nx != 0) --nx;
    return nx;
  }
  /// This sample's stratum: the dimension's own permutation of the strata
  /// (one per pixel and dimension), at the sample's index.
  std::uint32_t stratum(std::uint32_t dimension) const {
    const std::uint64_t h = mix64(m_key ^ (std::uint64_t(dimension) * 0x9E3779B97F4A7C15ull));
    return permutation_element(m_index % m_spp, m_spp, std::uint32_t(h));
  }
  /// Where in its stratum: random per sample and dimension.
  std::uint64_t jitter(std::uint32_t dimension) const {
    return mix64(m_key ^ (std::uint64_t(dimension) * 0xD1B54A32D192ED03ull) ^ (std::uint64_t(m_index) << 32));
  }
  /// Float rounding may carry (stratum + u) / n to 1: keep it below.
  static float within(float u) { return u < 1.0f ? u : 0x1.fffffep-1f; }

  std::uint64_t m_key;
  std::uint32_t m_index, m_spp, m_nx;
};

}  // namespace kappa
