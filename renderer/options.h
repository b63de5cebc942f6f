// Everything `kappa render` can be told, in one plain struct with defaults.
#pragma once

#include <cstdint>
#include <string>

namespace kappa {

struct RenderOptions {
  std::string scene;            ///< scene.json or .obj
  std::string accel = "naive";  ///< accelerator name (accel/accel.h)
  int spp = 64;                 ///< samples per pixel
  int max_depth = 32;           ///< bounces after the camera ray
  int rr_depth = 3;             ///< Russian roulette from this bounce on
  bool no_rr = false;           ///< disable Russian roulette
  std::uint64_t seed = 0;
  int threads = 0;              ///< 0 = all cores
  int width = 0, height = 0;    ///< 0 = the scene's film size
  std::string out;              ///< default out/<scene name>.exr
  std::string aov;              ///< comma list of albedo, normal, depth
  bool quiet = false;

  std::string to_string() const;
};

}  // namespace kappa
