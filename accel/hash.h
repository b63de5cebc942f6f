// A 64-bit mixing function (SplitMix64's finalizer, Steele et al. 2014):
// seeds the renderer's per-sample generators and picks which paths or rays
// statistics sample. Here, in the lowest library, so both can use it.
#pragma once

#include <cstdint>

namespace kappa {

constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace kappa
