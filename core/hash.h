// A 64-bit mixing function (SplitMix64's finalizer, Steele et al. 2014):
// seeds the renderer's per-sample generators and picks which paths or rays
// statistics sample; and FNV-1a for content hashes. Here, in the lowest
// library, so every layer can use them.
#pragma once

#include <cstdint>
#include <string_view>

namespace kappa {

/// FNV-1a 64 of `bytes`, continuing from `h` (chain several inputs): the
/// content hashes of the report's input_hash and converge's reference cache.
inline constexpr std::uint64_t kFnv1aOffset = 0xcbf29ce484222325ull;
constexpr std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t h = kFnv1aOffset) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace kappa
