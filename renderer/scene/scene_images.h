// The images a scene names, opened once at load through the OpenImageIO
// module: each texture map checked (readable, bounded, its texels usable)
// and given its TextureSystem handle, each opacity map read into its mask,
// the environment image read whole. A scene that names none never loads
// the module. Refusals name the MTL file and line (or scene.json) and exit 2.
#pragma once

#include <cstdint>

#include "core/error.h"
#include "renderer/scene/scene.h"

namespace kappa {

/// The most texels Kappa reads from one image (16384 x 16384): a larger one
/// is refused before any texel is read, never an out-of-memory.
inline constexpr std::uint64_t kMaxImageTexels = std::uint64_t(1) << 28;

void load_scene_images(Scene& scene, Warnings& warnings);

}  // namespace kappa
