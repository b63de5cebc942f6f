// Everything `kappa render` can be told, in one plain struct with defaults.
#pragma once

#include <cstdint>
#include <string>

namespace kappa {

struct RenderOptions {
  std::string scene;            ///< scene.json or .obj
  std::string accel = "grid";   ///< accelerator name (accel/accel.h)
  std::string grid_res = "auto";   ///< --grid-res: auto, N or NxNxN
  double grid_density = 0;         ///< --grid-density lambda (0 = the grid default)
  std::uint64_t grid_max_bytes = 0;  ///< --grid-max-bytes (0 = a quarter of RAM)
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
#ifdef KAPPA_NO_STATS
  std::string stats = "off";    ///< a build without statistics (-DKAPPA_STATS=OFF) has only off
#else
  std::string stats = "on";     ///< per-class counters during the render (grid only): on | off
#endif
  std::string report;           ///< per-frame JSON report path
  std::string cell_sample = "auto";  ///< per-cell counts for 1 path in N: auto | N
  std::string cell_map;         ///< --cell-map F.exr|png
  std::string cell_map_axis = "y";  ///< projection axis of the cell map
  std::string calibration;      ///< T0/Ts/Th file (default: kappa_calibration.json beside the executable)

  std::string to_string() const;
};

}  // namespace kappa
