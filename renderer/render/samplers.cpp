#include "renderer/render/samplers.h"

#include "core/input_error.h"

namespace kappa {

const char* sampler_name(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::independent: return "independent";
    case SamplerKind::stratified: return "stratified";
    case SamplerKind::sobol: return "sobol";
  }
  return "?";
}

SamplerKind parse_sampler(const std::string& name) {
  for (SamplerKind k : {SamplerKind::independent, SamplerKind::stratified, SamplerKind::sobol})
    if (name == sampler_name(k)) return k;
  throw InputError("--sampler: unknown sampler '" + name + "' (expected independent, stratified or sobol)");
}

std::uint32_t permutation_element(std::uint32_t i, std::uint32_t n, std::uint32_t seed) {
  // Kensler, "Correlated Multi-Jittered Sampling" (Pixar 2013): a hash
  // that is a bijection on the smallest power of two >= n, walked until it
  // lands inside [0, n).
  std::uint32_t w = n - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= seed;
    i *= 0xe170893du;
    i ^= seed >> 16;
    i ^= (i & w) >> 4;
    i ^= seed >> 8;
    i *= 0x0929eb3fu;
    i ^= seed >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | seed >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + seed) % n;
}

}  // namespace kappa
