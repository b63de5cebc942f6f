// The material record: what the renderer knows of a surface, whatever format
// it came from (an MTL today, read as Blender's importer reads it; glTF's
// metallic-roughness later). Its parameters are those of the one material
// model, glTF 2.0's metallic-roughness BSDF (renderer/bsdf/principled.h).
// The shading point (renderer/render/shading_point.h) hands it to the BSDF;
// the accelerators never see it.
#pragma once

#include <string>

#include "core/vec3.h"
#include "renderer/scene/texture_map.h"

namespace kappa {

struct Material {
  std::string name;
  Vec3f albedo{0.5f, 0.5f, 0.5f};  ///< base colour (Kd), in [0, 1]
  Vec3f emission{0, 0, 0};         ///< Ke, radiance (W sr^-1 m^-2, scene units), one-sided unless emits_both_sides
  /// Emits from its back too (glTF's doubleSided, as Cycles' emission does);
  /// an MTL's Ke emits towards its front only, as in pbrt and Mitsuba.
  bool emits_both_sides = false;
  float roughness = 1;             ///< perceptual roughness in [0, 1]; GGX alpha = roughness^2
  float metallic = 0;              ///< in [0, 1]: mix(dielectric, metal, metallic)
  /// In [0, 1]: the opaque dielectric's Fresnel is scaled by 2 * specular
  /// (0.5 the IOR's own reflectance, 0 none: a Lambertian surface).
  float specular = 0;
  float ior = 1.5f;                    ///< index of refraction inside (outside 1), > 0
  float transmission = 0;              ///< in [0, 1]: the dielectric's share that is glass
  Vec3f transmission_tint{1, 1, 1};    ///< multiplies refracted light (MTL Tf), in [0, 1]
  /// In [0, 1] (MTL d, 1 - Tr). Cut-outs are binary (glTF's MASK rule): a
  /// surface of opacity below 0.5 is skipped by every ray, at or above it is
  /// opaque; an opacity map decides per point (CutoutFilter).
  float opacity = 1;
  /// The texture maps that replace parameters above (Scene::texture_maps).
  MaterialMaps maps = kNoMaps;

  bool has_map(MapSlot s) const { return maps[std::size_t(s)] >= 0; }
  /// Some parameter other than opacity varies over the surface.
  bool textured() const {
    for (std::size_t s = 0; s < kMapSlots; ++s)
      if (s != std::size_t(MapSlot::opacity) && maps[s] >= 0) return true;
    return false;
  }
  /// Rays may pass through it: an opacity map, or a constant opacity below 0.5.
  bool cut_out() const { return has_map(MapSlot::opacity) || opacity < 0.5f; }

  /// It emits: a non-zero Ke, or an emission map (map_Ke replaces Ke, as in Blender).
  bool emissive() const {
    return emission.x > 0 || emission.y > 0 || emission.z > 0 || maps[std::size_t(MapSlot::emission)] >= 0;
  }
  /// Exactly today's Lambertian reflector (albedo / pi), the same everywhere
  /// and opaque: the all-Lambertian frame (path_variant.h) renders it with
  /// its own code.
  bool lambertian() const {
    return specular == 0 && metallic == 0 && transmission == 0 && !textured() && !cut_out();
  }
  /// Some light passes through (the glass part has weight): the surface has
  /// an inside and an outside; otherwise it reflects alike on both sides.
  bool refracts() const { return transmission > 0 && metallic < 1; }
};

}  // namespace kappa
