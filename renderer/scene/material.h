// The material record: what the renderer knows of a surface, whatever format
// it came from (an MTL today; glTF's metallic-roughness later). The shading
// point (renderer/render/shading_point.h) hands it to the BSDF; the
// accelerators never see it.
#pragma once

#include <string>

#include "core/vec3.h"

namespace kappa {

/// Lambertian reflector that may also emit (one-sided, towards its normal).
struct Material {
  std::string name;
  Vec3f albedo{0.5f, 0.5f, 0.5f};  ///< Kd, in [0, 1]
  Vec3f emission{0, 0, 0};         ///< Ke, radiance (W sr^-1 m^-2, scene units)

  bool emissive() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
};

}  // namespace kappa
