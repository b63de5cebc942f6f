// What each `kappa` subcommand can be told: plain structs holding the
// defaults docs/command-line.md documents, filled by the command line (command_line.cpp)
// and read by the commands (commands/).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "accel/factory.h"

namespace kappa {

struct RenderOptions {
  std::string scene;            ///< scene.json or .obj
  std::string accel = "grid2";  ///< accelerator name (accel/accel.h); grid when only grid flags are given
  AccelOptions build;           ///< --grid-res, --grid-density, --grid-max-bytes
  int spp = 64;                 ///< samples per pixel (with a budget: the cap, when given)
  bool spp_given = false;       ///< --spp was on the command line
  std::string sampler = "sobol";  ///< --sampler: independent | stratified | sobol (the most efficient: docs/command-line.md)
  std::string light_sampling = "mis";  ///< --light-sampling: mis | nee | bsdf
  std::string specialise = "on";  ///< --specialise: on | off (the general integrator, for measuring)
  std::string occluder_cache = "on";  ///< --occluder-cache: on | off (every shadow ray walked, for measuring)
  std::string time_budget;      ///< --time-budget: "500ms", "30s", "2m", "1h"
  bool time_budget_given = false;
  std::string target_relmse;    ///< --target-relmse, a number above 0
  bool target_relmse_given = false;
  bool adaptive = false;        ///< --adaptive: converged pixels stop sampling
  int adaptive_min_spp = 16;    ///< --adaptive-min-spp
  bool adaptive_min_spp_given = false;
  std::string checkpoint_every;  ///< --checkpoint-every: save the completed passes this often ("10m")
  bool checkpoint_every_given = false;
  bool resume = false;          ///< --resume: go on from the image's checkpoint
  int max_depth = 32;           ///< bounces after the camera ray
  int rr_depth = 5;             ///< Russian roulette from this bounce on (the most efficient: docs/command-line.md)
  bool no_rr = false;           ///< disable Russian roulette
  std::uint64_t seed = 0;
  int threads = 0;              ///< 0 = all cores
  int width = 0, height = 0;    ///< 0 = the scene's film size
  std::string camera;           ///< --camera NAME|INDEX: one of a glTF scene's cameras ("" = its first)
  std::string out;              ///< default out/<scene name>.exr
  std::string aov;              ///< comma list of albedo, normal, depth, cost, variance, spp
  bool quiet = false;
  std::string stats = "on";     ///< per-class counters during the render: on | off (kappa-nostats: off only)
  std::string report;           ///< per-frame JSON report path
  std::string cell_sample = "auto";  ///< per-cell counts for 1 path in N: auto | N
  std::string preview;          ///< --preview F.png|jpg|tif: an 8-bit sRGB picture beside the EXR
  double preview_exposure = 0;  ///< --preview-exposure EV: the preview's scale, 2^EV
  std::string cell_map;         ///< --cell-map F.exr|png
  std::string cell_map_axis = "y";  ///< projection axis of the cell map
  std::string calibration;      ///< T0/Ts/Th file (default: kappa_calibration.json beside the executable)
};

struct CastOptions {
  std::string scene;
  std::string rays = "lines";  ///< lines | segments | camera | bounce | shadow
  std::size_t n = 1000000;
  std::string accel = "grid";
  AccelOptions build;          ///< grid_max_bytes also bounds the per-cell counters
  std::uint64_t seed = 0;
  double length = 0;  ///< segment length; 0 = two mean cell widths
  int threads = 0;
  std::string report;  ///< JSON report path
  bool quiet = false;
};

struct BenchOptions {
  std::string scene;
  std::vector<std::string> accels = {"naive", "grid", "grid2", "embree", "embree-fast"};
  std::vector<std::string> rays = {"camera", "bounce", "shadow", "lines"};
  std::vector<int> threads = {1, 2};
  int repeat = 3;
  std::size_t n = std::size_t(1) << 20;  ///< rays per class
  std::uint64_t seed = 0;
  std::string json;        ///< write the figures here too
  AccelOptions build;
  double naive_budget_s = 60;  ///< skip naive when its estimated time exceeds this
};

struct CalibrateOptions {
  std::vector<std::string> scenes;  ///< default: the Cornell box and the low-resolution bunny in assets/
  std::vector<double> densities = {2, 8, 32, 128, 512};
  int spp = 16;   ///< samples per pixel of each calibration frame (the cost issue's renders use 16)
  int size = 64;   ///< each calibration frame is the centre size x size pixels of the scene's film
  int repeat = 3;
  int threads = 0;  ///< threads walking at once (0 = all cores, as a render runs)
  AccelOptions build;  ///< grid_max_bytes only: the densities set the resolutions
  std::string out;  ///< default: default_calibration_path()
  bool no_generated = false;  ///< measure only the scenes given, not the generated soups too
};

}  // namespace kappa

namespace kappa {

struct ConvergeOptions {
  RenderOptions render;  ///< every curve's settings before its --vary (--spp, outputs and budgets unused)
  std::string reference;  ///< reference EXR; empty: a self-made one, cached
  std::string cache;      ///< where self-made references are kept (default: references/ beside the executable)
  std::vector<int> spp = {1, 2, 4, 8, 16, 32, 64, 128, 256};  ///< where the error is measured
  std::vector<std::string> vary;  ///< KEY=V1,V2,...
  std::string json;  ///< the curves and the ranking
  std::string plot;  ///< a PNG made by tools/converge_plot.py
  double equal_time_s = 0;  ///< rank at this render time (0: the longest time every setting reached)
};

}  // namespace kappa

namespace kappa {

struct SweepOptions {
  std::string scene;
  std::string grid_density;  ///< "A:B": lambda from A to B (the default, 1:1024, when neither range is given)
  std::string grid_res;      ///< "A:B": N_c from A^3 to B^3
  int steps = 11;            ///< points, geometric in N_c
  std::vector<std::string> rays = {"camera", "bounce", "shadow", "lines"};
  std::size_t n = std::size_t(1) << 18;  ///< rays per class
  int repeat = 3;            ///< timed passes per point and class (the median is reported)
  int threads = 1;           ///< threads tracing each timed pass (seconds per ray are thread-seconds at 1)
  std::uint64_t seed = 0;
  std::uint64_t grid_max_bytes = 0;  ///< a point whose grid would exceed it is skipped; 0 = a quarter of RAM
  std::string calibration;   ///< cost-model constants (default: beside the executable, else built in)
  std::string json;
  std::string plot;
  bool quiet = false;
};

}  // namespace kappa
