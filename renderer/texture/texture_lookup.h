// Texture maps looked up at a shading point (the general path variant's
// vertices only: a scene without maps never calls here): the maps' texels
// through OpenImageIO's TextureSystem, filtered over the footprint the
// camera ray's differentials give (uv_footprint.h), decoded from sRGB where
// Blender decodes (8- and 16-bit files), then clamped to what the BSDF
// accepts. Colour to scalar is the luminance, Blender's implicit conversion.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/srgb.h"
#include "core/vec2.h"
#include "renderer/bsdf/principled.h"
#include "renderer/scene/scene.h"
#include "renderer/image/image_library.h"

namespace kappa {

/// How far the lookup point moves in (u, v) per pixel: zero for a point
/// lookup (the finest level, bilinear).
struct UvFootprint {
  float dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};

/// A texel value the BSDF can use: NaN and negatives (warned about at load) 0.
inline float usable(float v, float hi) { return v > 0.0f ? std::min(v, hi) : 0.0f; }

/// The lookup's coordinates and footprint in the image (placement applied).
inline TextureCoords texture_coords(const TextureMap& map, Vec2f uv, const UvFootprint& fp) {
  TextureCoords at;
  at.s = uv.u * map.scale.u + map.offset.u;
  at.t = 1.0f - (uv.v * map.scale.v + map.offset.v);  // v runs up, the image's rows down
  at.dsdx = fp.dudx * map.scale.u;
  at.dsdy = fp.dudy * map.scale.u;
  at.dtdx = -fp.dvdx * map.scale.v;
  at.dtdy = -fp.dvdy * map.scale.v;
  return at;
}

/// The map's colour at (u, v): RGB, a grey file's one channel repeated,
/// times its factor.
inline Vec3f lookup_colour(const TextureMap& map, Vec2f uv, const UvFootprint& fp, float hi) {
  float c[3] = {0, 0, 0};
  const int count = map.channels >= 3 ? 3 : 1;
  image_library().lookup(map.handle, map.wrap_s, map.wrap_t, TextureFilter::filtered, 0, count,
                         texture_coords(map, uv, fp), c);
  if (count == 1) c[1] = c[2] = c[0];
  for (float& v : c) v = usable(map.srgb ? srgb_to_linear(v) : v, hi);
  return {usable(c[0] * map.factor.x, hi), usable(c[1] * map.factor.y, hi), usable(c[2] * map.factor.z, hi)};
}

/// A scalar map: its channel (glTF), else the luminance of its colour (the
/// value of a grey file), times its factor.
inline float lookup_scalar(const TextureMap& map, Vec2f uv, const UvFootprint& fp) {
  // A grey (or grey and alpha) file is grey in every colour channel, as
  // glTF expands it: its luminance is its grey.
  if (map.scalar_channel < 0 || map.channels < 3 || map.scalar_channel >= map.channels) {
    const Vec3f c = lookup_colour(map, uv, fp, 1.0f);
    return usable(0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z, 1.0f);
  }
  float v = 0;
  image_library().lookup(map.handle, map.wrap_s, map.wrap_t, TextureFilter::filtered, map.scalar_channel, 1,
                         texture_coords(map, uv, fp), &v);
  return usable(usable(map.srgb ? srgb_to_linear(v) : v, 1.0f) * map.factor.x, 1.0f);
}

/// `p` (the material's constants) with its maps' values where it has maps.
inline void apply_texture_maps(const Scene& scene, const Material& m, Vec2f uv, const UvFootprint& fp,
                               bsdf::PrincipledParams& p) {
  auto map = [&](MapSlot s) -> const TextureMap* {
    const std::int32_t k = m.maps[std::size_t(s)];
    return k >= 0 ? &scene.texture_maps[std::size_t(k)] : nullptr;
  };
  if (const TextureMap* t = map(MapSlot::base_color)) p.base = lookup_colour(*t, uv, fp, 1.0f);
  if (const TextureMap* t = map(MapSlot::roughness)) p.roughness = lookup_scalar(*t, uv, fp);
  if (const TextureMap* t = map(MapSlot::metallic)) p.metallic = lookup_scalar(*t, uv, fp);
  if (const TextureMap* t = map(MapSlot::specular)) p.specular = lookup_scalar(*t, uv, fp);
}

/// The radiance `m` emits at (u, v): its emission map's texel (decoded, not
/// clipped: a float map may be brighter than 1), or Ke.
inline Vec3f emitted(const Scene& scene, const Material& m, Vec2f uv) {
  const std::int32_t k = m.maps[std::size_t(MapSlot::emission)];
  if (k < 0) return m.emission;
  return lookup_colour(scene.texture_maps[std::size_t(k)], uv, UvFootprint{}, INFINITY);
}

}  // namespace kappa
