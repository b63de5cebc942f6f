// What sampling a lobe returns, and the lobes a bounce ray is counted by.
#pragma once

#include <array>
#include <cstddef>

#include "core/vec3.h"

namespace kappa::bsdf {

/// The kind of scattering that sampled a bounce ray: the report's
/// rays.bounce_by_lobe keys. A rough microfacet reflection is glossy, a delta
/// one (mirror, smooth glass's reflection) specular; every refraction is
/// transmission.
enum class Lobe : unsigned char { diffuse = 0, glossy = 1, specular = 2, transmission = 3 };
inline constexpr std::size_t kLobes = 4;
inline constexpr std::array<const char*, kLobes> kLobeNames = {"diffuse", "glossy", "specular", "transmission"};

struct LobeSample {
  Vec3f f;            ///< the BSDF's value for (wo, wi) (not times the cosine)
  Vec3f wi;           ///< the sampled direction, unit, local frame
  float pdf = 0;      ///< solid-angle density, or the discrete probability of a delta lobe
  float etap = 1;     ///< relative index crossed (1 unless refracted)
  Lobe lobe = Lobe::diffuse;
  bool delta = false;  ///< f and pdf are the weights of a Dirac delta
};

}  // namespace kappa::bsdf
