// A texture map a material names (an MTL's map_Kd, map_d, ...): which file,
// where it was named, and how its coordinates are placed. The scene loader
// records it; load_scene_images (renderer/texture/) opens it through the
// OpenImageIO module and fills in what the lookups need.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec2.h"
#include "core/vec3.h"

namespace kappa {

/// The material parameter a map drives.
enum class MapSlot : unsigned char { base_color, specular, roughness, metallic, emission, opacity };
inline constexpr std::size_t kMapSlots = 6;

struct TextureMap {
  MapSlot slot = MapSlot::base_color;
  std::filesystem::path file;         ///< resolved against the MTL file's folder
  std::filesystem::path declared_in;  ///< the MTL file
  std::size_t line = 0;               ///< its line there
  std::string keyword;                ///< map_Kd, map_d, ...
  /// The lookup's coordinates are (u, v) * scale + offset (-s and -o, as
  /// Blender's Mapping node applies them: scale, then offset).
  Vec2f scale{1, 1}, offset{0, 0};
  bool clamp = false;  ///< -clamp on: coordinates outside [0, 1] read the edge; else the image repeats

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
};

/// Per slot, the index of the map in Scene::texture_maps, or -1.
using MaterialMaps = std::array<std::int32_t, kMapSlots>;
inline constexpr MaterialMaps kNoMaps = {-1, -1, -1, -1, -1, -1};

}  // namespace kappa
