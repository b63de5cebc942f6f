// A texture map a material names (an MTL's map_Kd, map_d, ...): which file,
// where it was named, and how its coordinates are placed. The scene loader
// records it; load_scene_images (renderer/texture/) opens it through the
// OpenImageIO module and fills in what the lookups need.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "core/vec3.h"
#include "renderer/image/image_library.h"

namespace kappa {

/// The material parameter a map drives.
enum class MapSlot : unsigned char { base_color, specular, roughness, metallic, emission, opacity };
inline constexpr std::size_t kMapSlots = 6;

struct TextureMap {
  MapSlot slot = MapSlot::base_color;
  std::filesystem::path file;         ///< resolved against the MTL (glTF) file's folder
  std::filesystem::path declared_in;  ///< the MTL or glTF file
  std::size_t line = 0;               ///< its line there (0 in a glTF file)
  std::string keyword;                ///< map_Kd, map_d, ... or the glTF element's JSON pointer
  /// The image's bytes when the scene file holds it (a glTF buffer view or
  /// data URI): `file` is then a name, "scene.glb#images/3.png", that the
  /// image library reads from memory.
  std::shared_ptr<const std::vector<unsigned char>> embedded;
  /// The lookup's coordinates are (u, v) * scale + offset (-s and -o, as
  /// Blender's Mapping node applies them: scale, then offset).
  Vec2f scale{1, 1}, offset{0, 0};
  /// Outside [0, 1] (glTF's sampler wrapS, wrapT; an MTL's images repeat).
  TextureWrap wrap_s = TextureWrap::periodic, wrap_t = TextureWrap::periodic;
  /// Multiplies what the lookup gives (glTF's baseColorFactor, emissiveFactor
  /// × emissive strength, metallic and roughness factors in x): 1 for an MTL,
  /// whose maps replace the constant.
  Vec3f factor{1, 1, 1};
  /// A scalar map reads this channel (glTF: roughness G = 1, metallic B = 2);
  /// -1: the luminance of its colour, Blender's implicit conversion.
  int scalar_channel = -1;
  /// Never decoded from sRGB (glTF's metallic-roughness texture is linear
  /// data); otherwise decoded when stored in 8 or 16 bits, as Blender does.
  bool linear = false;
  /// An opacity map: opaque where alpha × alpha_factor ≥ alpha_cutoff (glTF's
  /// MASK: baseColorFactor's alpha and alphaCutoff; an MTL's map_d: 1, 0.5).
  float alpha_factor = 1, alpha_cutoff = 0.5f;
  /// An opacity map without an alpha channel is warned about (an MTL's map_d:
  /// Blender reads its alpha, so the surface stays opaque); glTF defines its
  /// alpha as 1, which alpha_factor and alpha_cutoff then decide.
  bool warn_without_alpha = true;

  // Filled by load_scene_images:
  void* handle = nullptr;    ///< the TextureSystem's handle
  bool srgb = false;         ///< a colour map stored in 8 or 16 bits: decoded from sRGB after the lookup
  int first_channel = 0;     ///< the channel a scalar map reads (opacity: the alpha channel, if any)
  int channels = 0;          ///< the file's channel count
  std::int32_t mask = -1;    ///< an opacity map's index in Scene::opacity_masks
  /// An emission map's mean radiance over its texels (decoded): what the
  /// light's power is, for choosing it among the lights.
  Vec3f mean{0, 0, 0};
};

/// An opacity map as the visibility queries test it (CutoutFilter): its
/// finest level, one byte a texel, 1 where the opacity is 0.5 or more; the
/// texel a point falls in decides (no filtering: one answer per point, the
/// same for every accelerator).
struct OpacityMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> opaque;  ///< row 0 at the image's top
  Vec2f scale{1, 1}, offset{0, 0};   ///< its map's placement (TextureMap)
  TextureWrap wrap_s = TextureWrap::periodic, wrap_t = TextureWrap::periodic;  ///< and its wrap
};

/// Per slot, the index of the map in Scene::texture_maps, or -1.
using MaterialMaps = std::array<std::int32_t, kMapSlots>;
inline constexpr MaterialMaps kNoMaps = {-1, -1, -1, -1, -1, -1};

}  // namespace kappa
